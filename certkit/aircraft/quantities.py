"""Pydantic field types for physical quantities.

A quantity in the aircraft file is either a bare number, taken as SI, or a string with a unit
("4927.3 ft^2", "97300 lbf", "43000 ft"), converted with pint (:mod:`certkit.units`). After
validation every field holds a float in SI.

A speed also states its kind: ``"340 kn EAS"``, ``"340 KEAS"``, ``{value: 340 kn, kind: CAS}``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Annotated, Any, Callable, Literal, TypeAlias

import numpy as np
from pydantic import BaseModel, BeforeValidator, ConfigDict, Discriminator, Field, Tag, WithJsonSchema, model_validator

from certkit.units import DIMENSIONS, UnitError, to_si


def _quantity_schema(dimension: str) -> dict[str, object]:
    unit = DIMENSIONS[dimension] or "1"
    return {
        "anyOf": [{"type": "number"}, {"type": "string"}],
        "description": f"{dimension}: a number in {unit} or a string with a unit",
    }


def _converter(dimension: str) -> Callable[[object], object]:
    def convert(value: object) -> object:
        if isinstance(value, bool):
            raise ValueError(
                f"expected a {dimension} (a number in {DIMENSIONS[dimension] or 'no unit'} or a string "
                f"with a unit), not a yes/no value"
            )
        if isinstance(value, (str, int, float)):
            try:
                return to_si(value, dimension)
            except UnitError as exc:
                raise ValueError(str(exc)) from None
        return value  # let pydantic report the wrong type

    return convert


def quantity(dimension: str) -> object:
    """``Annotated[float, ...]`` accepting a number in SI or a string with a unit of ``dimension``."""
    return Annotated[float, BeforeValidator(_converter(dimension)), WithJsonSchema(_quantity_schema(dimension))]


if TYPE_CHECKING:  # a quantity is a float once validated: what a type checker should see
    Length: TypeAlias = float
    Area: TypeAlias = float
    Mass: TypeAlias = float
    Force: TypeAlias = float
    Moment: TypeAlias = float
    Angle: TypeAlias = float
    Inertia: TypeAlias = float
    Time: TypeAlias = float
    SpeedValue: TypeAlias = float
    Pressure: TypeAlias = float
    Gearing: TypeAlias = float
    Stiffness: TypeAlias = float
    Density: TypeAlias = float
    ArealDensity: TypeAlias = float
    AngularRate: TypeAlias = float
    Acceleration: TypeAlias = float
    MassPerEnergy: TypeAlias = float
    Temperature: TypeAlias = float
    SpecificFuelConsumption: TypeAlias = float
else:
    Length = quantity("length")
    Area = quantity("area")
    Mass = quantity("mass")
    Force = quantity("force")
    Moment = quantity("moment")
    Angle = quantity("angle")
    Inertia = quantity("inertia")
    Time = quantity("time")
    SpeedValue = quantity("speed")
    Pressure = quantity("pressure")
    Gearing = quantity("gearing")
    Stiffness = quantity("stiffness")
    Density = quantity("density")
    ArealDensity = quantity("areal_density")
    AngularRate = quantity("angular_rate")
    Acceleration = quantity("acceleration")
    MassPerEnergy = quantity("mass_per_energy")
    Temperature = quantity("temperature")
    SpecificFuelConsumption = quantity("specific_fuel_consumption")

PositiveLength = Annotated[Length, Field(gt=0)]
PositiveArea = Annotated[Area, Field(gt=0)]
PositiveMass = Annotated[Mass, Field(gt=0)]
PositiveForce = Annotated[Force, Field(gt=0)]
Fraction = Annotated[float, Field(ge=0.0, le=1.0)]

SpeedKind = Literal["EAS", "CAS", "TAS"]
_KIND_SUFFIXES = {
    "EAS": ("EAS", None),
    "CAS": ("CAS", None),
    "TAS": ("TAS", None),
    "KEAS": ("EAS", "kn"),
    "KCAS": ("CAS", "kn"),
    "KTAS": ("TAS", "kn"),
}


class Speed(BaseModel):
    """An airspeed in m/s with its kind (EAS, CAS or TAS)."""

    model_config = ConfigDict(
        extra="forbid",
        frozen=True,
        allow_inf_nan=False,
        json_schema_extra={
            "description": 'a speed with its kind: "340 kn EAS", "340 KEAS" or {value: "340 kn", kind: EAS}'
        },
    )

    value: Annotated[SpeedValue, Field(gt=0)]
    kind: SpeedKind

    @model_validator(mode="before")
    @classmethod
    def _from_text(cls, data: object) -> object:
        if isinstance(data, bool) or isinstance(data, (int, float)):
            raise ValueError("a speed must state its kind: write for example '340 kn EAS' (EAS, CAS or TAS)")
        if isinstance(data, str):
            parts = data.split()
            if not parts or parts[-1].upper() not in _KIND_SUFFIXES:
                raise ValueError(f"{data!r}: a speed must end with its kind, e.g. '340 kn EAS' or '340 KEAS'")
            kind, unit = _KIND_SUFFIXES[parts[-1].upper()]
            number = " ".join(parts[:-1]) + (f" {unit}" if unit else "")
            if not parts[:-1]:
                raise ValueError(f"{data!r}: no value before the speed kind")
            return {"value": number.strip(), "kind": kind}
        return data

    def value_at(self, altitude: Any) -> Any:
        """The speed (m/s, of its kind) at pressure ``altitude`` (m): the same at every altitude."""
        return self.value + 0.0 * np.asarray(altitude, dtype=float)


class SpeedSchedule(BaseModel):
    """A design speed scheduled with altitude (§25.335(c)(2): VA "evaluated at the design weight and altitude"):
    speeds of one kind at increasing pressure altitudes, linear between them and held beyond; ``value`` is the
    lowest altitude's (the sea-level speed where the schedule starts there)."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    kind: SpeedKind
    altitude: Annotated[list[Length], Field(min_length=2, description="pressure altitudes, increasing")]
    speed: Annotated[list[Annotated[SpeedValue, Field(gt=0)]], Field(min_length=2, description="one per altitude")]
    source: str = Field(min_length=1)

    @model_validator(mode="after")
    def _table(self) -> "SpeedSchedule":
        if len(self.altitude) != len(self.speed):
            raise ValueError(f"{len(self.altitude)} altitudes but {len(self.speed)} speeds: one speed per altitude")
        if any(b <= a for a, b in zip(self.altitude, self.altitude[1:])):
            raise ValueError(f"altitude {[round(h, 1) for h in self.altitude]} m must increase strictly")
        return self

    @property
    def value(self) -> float:
        """The lowest altitude's speed (m/s)."""
        return float(self.speed[0])

    def value_at(self, altitude: Any) -> Any:
        """The speed (m/s, of its kind) at pressure ``altitude`` (m), linear in altitude between the entries."""
        return np.interp(np.asarray(altitude, dtype=float), self.altitude, self.speed)


def _speed_or_schedule(data: Any) -> str:
    """A mapping with ``altitude`` is a schedule; anything else a single speed."""
    if isinstance(data, dict):
        return "schedule" if "altitude" in data else "speed"
    return "schedule" if isinstance(data, SpeedSchedule) else "speed"


#: a design speed: one speed, or a schedule with altitude (errors reported against the form given)
SpeedOrSchedule = Annotated[
    Annotated[Speed, Tag("speed")] | Annotated[SpeedSchedule, Tag("schedule")],
    Discriminator(_speed_or_schedule),
]


__all__ = [
    "Length",
    "Area",
    "Mass",
    "Force",
    "Moment",
    "Angle",
    "Inertia",
    "Time",
    "SpeedValue",
    "Pressure",
    "Gearing",
    "Stiffness",
    "Density",
    "ArealDensity",
    "AngularRate",
    "Acceleration",
    "MassPerEnergy",
    "PositiveLength",
    "PositiveArea",
    "PositiveMass",
    "PositiveForce",
    "Fraction",
    "Speed",
    "SpeedKind",
    "SpeedSchedule",
    "SpeedOrSchedule",
    "quantity",
]
