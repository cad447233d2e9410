"""Pydantic field types for physical quantities.

A quantity in the aircraft file is either a bare number, taken as SI, or a string with a unit
("4927.3 ft^2", "97300 lbf", "43000 ft"), converted with pint (:mod:`certkit.units`). After
validation every field holds a float in SI.

A speed also states its kind: ``"340 kn EAS"``, ``"340 KEAS"``, ``{value: 340 kn, kind: CAS}``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Annotated, Callable, Literal, TypeAlias

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, WithJsonSchema, model_validator

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
    "quantity",
]
