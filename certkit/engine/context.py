"""The Context: the aircraft and its shared models, built lazily and memoised.

Two rules that need the same model evaluation (a trim, a stall speed, an aerodynamic model of a
configuration) compute it once per run and process. Rules compute through the Context; models
know nothing of regulations.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Callable, Hashable, TypeVar

import numpy as np

from certkit.aircraft import Aircraft, LoadedAircraft
from certkit.atmosphere import convert_speed
from certkit.models.aero.airplane import AirplaneAero, build_airplane_aero, lattice_derivatives
from certkit.models.aero.planform import lift_curve_slope, sweep_at

if TYPE_CHECKING:
    from collections.abc import Iterable, Mapping

    from certkit.engine.results import Condition
    from certkit.models.aero.lattice_store import LatticeStore
    from certkit.models.dynamics.linearize import Linearization
    from certkit.models.dynamics.modes import Mode
    from certkit.models.dynamics.trim import TrimBatch
    from certkit.models.mass.loading import Loading

T = TypeVar("T")

#: the Mach number that limits each design speed at altitude
MACH_OF = {"VC": "MC", "VD": "MD", "VMO": "MMO", "VFC": "MFC"}


class Context:
    """``lattice_store`` (optional): a folder of vortex-lattice solutions kept between runs
    (:class:`~certkit.models.aero.lattice_store.LatticeStore`) the aerodynamic models take theirs from."""

    def __init__(self, loaded: LoadedAircraft, lattice_store: LatticeStore | None = None):
        self.loaded = loaded
        self.lattice_store = lattice_store
        self.aircraft: Aircraft = loaded.model
        self._memo: dict[Hashable, object] = {}
        self._loading_names: dict[Hashable, set[str]] = {}
        self.notes: list[str] = []
        self.hits = 0
        self.misses = 0

    def memo(self, key: Hashable, compute: Callable[[], T]) -> T:
        """Return the cached value of ``key``, computing it once."""
        try:
            value = self._memo[key]
            self.hits += 1
            return value  # type: ignore[return-value]
        except KeyError:
            self.misses += 1
            value = self._memo[key] = compute()
            return value

    def share_aerodynamics(self, other: "Context") -> None:
        """Reuse ``other``'s vortex lattice and aerodynamic models: valid when the two aircraft differ only in mass
        data (the design layer's sizing loop changes the tail's mass, CG, inertia and structural capability, not its
        geometry). The loads models share their aerodynamic tables (kept with the lattice's unit solutions), not the
        models themselves: their strip masses come from the mass table."""
        for key, value in other._memo.items():
            if key == "lattice_derivatives" or (isinstance(key, tuple) and key[:1] == ("aero",)):
                self._memo.setdefault(key, value)

    def provenance(self) -> dict[str, Any]:
        """What the shared models were built from, for the report: aerodynamic sources, overrides and
        notes per configuration, every loading solved (mass, CG, inertia, payload, fuel, notes), and the
        empty airplane's component table."""
        from certkit.models.mass.loading import (  # deferred: mass model: `certkit derivatives` builds the aero only
            Loading,
            empty_airplane,
        )

        aero: dict[str, dict[str, Any]] = {}
        loadings: dict[Any, dict[str, Any]] = {}
        for key, value in self._memo.items():
            if isinstance(value, AirplaneAero):
                aero[value.configuration] = {
                    "source": value.source,
                    "mach": list(value.mach),
                    "overrides": value.overrides,
                    "notes": value.notes,
                }
            elif isinstance(value, Loading):
                p = value.properties
                names = self._loading_names.get(key) or {value.name}
                loadings[key] = {
                    "name": " / ".join(sorted(names)),
                    "mass_kg": p.mass,
                    "x_cg_m": float(p.cg[0]),
                    "payload_kg": value.payload,
                    "fuel_kg": value.fuel,
                    "Ixx": p.Ixx,
                    "Iyy": p.Iyy,
                    "Izz": p.Izz,
                    "Ixz": p.Ixz,
                    "built": value.construction,
                    "notes": list(value.notes),
                }
        components, notes = empty_airplane(self.aircraft)
        warning = self.inertia_warning()
        notes = notes + ([f"warning: {warning}"] if warning else [])
        return {
            "aerodynamics": aero,
            "loadings": [loadings[k] for k in sorted(loadings)],
            "components": [
                {
                    "item": c.name,
                    "mass_kg": c.mass,
                    "x_m": c.cg[0],
                    "y_m": c.cg[1],
                    "z_m": c.cg[2],
                    "own_inertia": c.inertia is not None,
                }
                for c in components
            ],
            "component_notes": notes,
        }

    def inertia_warning(self) -> str | None:
        """Declared inertia vs component build-up beyond the file's tolerance (:func:`inertia_comparison`), once."""
        from certkit.models.mass.loading import (  # deferred: mass model: `certkit derivatives` builds the aero only
            inertia_comparison,
        )

        return self.memo("inertia_comparison", lambda: inertia_comparison(self.aircraft))

    def lookup(self, dotted: str) -> object:
        """The aircraft-file value at ``speeds.VMC`` / ``configurations.landing.CLmax`` (None if absent)."""
        node: object = self.aircraft
        for part in dotted.split("."):
            if node is None:
                return None
            if isinstance(node, dict):
                node = node.get(part)
            else:
                node = getattr(node, part, None)
        if isinstance(node, (dict, list)) and not node:
            return None
        return node

    def missing(self, paths: tuple[str, ...]) -> list[str]:
        return [p for p in paths if self.lookup(p) is None]

    # --- shared models (each lazily built and memoised) ---------------------------------

    def aero(self, configuration: str) -> AirplaneAero:
        """The aerodynamic model of ``configuration`` (:mod:`certkit.models.aero.airplane`), built once;
        the vortex lattice is shared by every configuration."""

        def build() -> AirplaneAero:
            declared = configuration in self.aircraft.aerodynamics.derivative_tables
            solve = lattice_derivatives if self.lattice_store is None else self.lattice_store.derivatives
            lattice = None if declared else self.memo("lattice_derivatives", lambda: solve(self.aircraft))
            return build_airplane_aero(self.aircraft, configuration, lattice=lattice)

        return self.memo(("aero", configuration), build)

    def clmax(self, configuration: str, mach: float | None = None) -> float | None:
        """The declared CLmax of ``configuration`` (the low-speed value of the stall speeds), or at ``mach`` where the
        configuration declares it against Mach (``CLmax_by_mach``); None when not declared."""
        cfg = self.aircraft.configurations.get(configuration)
        if cfg is None or cfg.CLmax is None:
            return None
        return cfg.CLmax if mach is None else float(cfg.clmax_at(mach))

    def wing_lift_slope(self, mach: float) -> float:
        """Wing lift-curve slope per radian (DATCOM/Polhamus; see :mod:`certkit.models.aero.planform`)."""
        if self.aircraft.geometry is None:
            raise ValueError("geometry is not declared")
        w = self.aircraft.geometry.wing
        key = ("wing_lift_slope", round(float(mach), 4))
        return self.memo(
            key,
            lambda: float(
                lift_curve_slope(
                    w.aspect_ratio, sweep_at(0.5, w.sweep_quarter_chord, w.aspect_ratio, w.taper), float(mach)
                )
            ),
        )

    def design_speed_eas(self, name: str, altitude: Any) -> tuple[np.ndarray, np.ndarray]:
        """Declared design speed ``name`` (VC, VD, VMO, VB, VA …) as EAS (m/s) at ``altitude``, limited by
        its Mach counterpart (MC, MD, MMO) where declared; returns (speed, mach_limited). Memoised (the loads
        rules ask for the same speeds at the same altitudes for every condition); the arrays returned are copies."""
        h = np.asarray(altitude, dtype=float)
        key = ("design_speed_eas", name, h.shape, tuple(h.ravel().tolist()))
        speed, limited = self.memo(key, lambda: self._design_speed_eas(name, h))
        return speed.copy(), limited.copy()

    def design_speed_eas_at(self, name: str, altitude: float) -> float:
        """:meth:`design_speed_eas` of one altitude as a float, memoised on (name, altitude): the loads rules ask it
        for each condition's altitude about ten thousand times a design (the same value, without the arrays)."""
        key = ("design_speed_eas_at", name, altitude)
        try:
            return self._memo[key]  # type: ignore[return-value]
        except KeyError:
            value = self._memo[key] = float(self.design_speed_eas(name, altitude)[0])
            return value

    def _design_speed_eas(self, name: str, h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        speed = getattr(self.aircraft.speeds, name)
        mach = getattr(self.aircraft.speeds, MACH_OF.get(name, ""), None)
        eas = np.full(h.shape, np.inf) if speed is None else convert_speed(speed.value_at(h), speed.kind, "EAS", h)
        eas_m = np.full(h.shape, np.inf) if mach is None else convert_speed(mach, "MACH", "EAS", h)
        if speed is None and mach is None:
            raise ValueError(f"speeds.{name} is not declared")
        return np.minimum(eas, eas_m), eas_m < eas

    # --- flight: loadings, trims and modes of conditions (batched, memoised) --------------

    def loading(self, mass: float, x_cg: float, name: str = "") -> Loading:
        """Payload/fuel distribution and inertia reaching (mass, x_cg) (:mod:`certkit.models.mass.loading`)."""
        from certkit.models.mass.loading import (  # deferred: mass model: `certkit derivatives` builds the aero only
            solve_loading,
        )

        key = ("loading", round(float(mass), 3), round(float(x_cg), 6))
        if name:  # one loading may be asked for under several names (a corner and a design weight's CG limit)
            self._loading_names.setdefault(key, set()).add(name)
        return self.memo(key, lambda: solve_loading(self.aircraft, mass, x_cg, name))

    def trim(
        self,
        conditions: Iterable[Condition],
        kind: str = "straight",
        *,
        gamma: Any = 0.0,
        bank: Any = 0.0,
        beta: Any = 0.0,
        inoperative: str | Iterable[str] | None = None,
        configuration: str | None = None,
        design_limits: bool = True,
        throttle: Any = None,
        stabilizer: Any = None,
        initial: Mapping[str, Any] | None = None,
    ) -> TrimBatch:
        """Trim every condition (its loading, configuration, altitude and speed) in one batch.

        Returns a :class:`certkit.models.dynamics.trim.TrimBatch`; ``gamma``, ``bank``, ``beta`` are scalars or one
        value per condition (rad); ``inoperative`` names a failed engine (or gives one name per condition);
        ``throttle`` fixes the throttles (0–1, the flight-path angle is then solved for). Control limits are the design
        limits, a movable stabiliser's those of the configuration. An airplane with a movable stabiliser trims it (the
        elevator at its trim setting); ``stabilizer`` (rad, deflection from the datum as in ``TrimBatch.u``, a scalar or
        one per condition) holds it there instead and solves for the elevator — a change without re-trimming, or a
        manoeuvre from a trim (a held stabiliser may lie beyond the new configuration's trim limits: those limit
        trimming, not where the stabiliser already is). ``initial`` warm-starts the trims (see
        :func:`certkit.models.dynamics.trim.trim`).
        """
        from certkit.engine.conditions import (  # deferred: mass model: `certkit derivatives` builds the aero only
            speed_as,
        )

        conds = tuple(conditions)
        configs = {configuration or c.configuration for c in conds}
        if len(configs) != 1 or None in configs:
            raise ValueError(f"a trim batch needs one configuration, got {sorted(map(str, configs))}")
        config = configs.pop()
        assert config is not None  # checked above
        tas = np.array([speed_as(c, "TAS") for c in conds])
        h = np.array([c.altitude or 0.0 for c in conds])
        key: tuple[Any, ...] = (
            "trim",
            config,
            tuple((c.mass, c.x_cg) for c in conds),
            tuple(np.round(tas, 6)),
            tuple(h),
            kind,
            _hashable(gamma),
            _hashable(bank),
            _hashable(beta),
            inoperative if inoperative is None or isinstance(inoperative, str) else tuple(inoperative),
            design_limits,
            None if throttle is None else _hashable(throttle),
        )
        if stabilizer is not None:
            key += ("stabilizer", _hashable(stabilizer))
        if initial is not None:
            key += ("initial",) + tuple((k, _hashable(v)) for k, v in sorted(initial.items()))
        return self.memo(
            key,
            lambda: self._trim(
                conds,
                config,
                tas,
                h,
                kind,
                gamma,
                bank,
                beta,
                inoperative,
                design_limits,
                throttle,
                stabilizer,
                initial,
            ),
        )

    def _trim(
        self,
        conds: tuple[Condition, ...],
        config: str,
        tas: np.ndarray,
        h: np.ndarray,
        kind: str,
        gamma: Any,
        bank: Any,
        beta: Any,
        inoperative: str | Iterable[str] | None,
        design_limits: bool,
        throttle: Any = None,
        stabilizer: Any = None,
        initial: Mapping[str, Any] | None = None,
    ) -> TrimBatch:
        from certkit.models.dynamics.trim import trim  # deferred: dynamics: `certkit derivatives` builds the aero only
        from certkit.models.flight import (  # deferred: dynamics: `certkit derivatives` builds the aero only
            ROLES,
            control_limits,
            flight_model,
            model_stabilizer,
        )

        loadings = [self.loading(_number(c.mass), _number(c.x_cg), c.loading or "") for c in conds]
        operative = None
        if inoperative is not None:
            if self.aircraft.propulsion is None:
                raise ValueError("an inoperative engine needs the propulsion section")
            names = [e.name for e in self.aircraft.propulsion.engines]
            dead = [inoperative] * len(conds) if isinstance(inoperative, str) else list(inoperative)
            for d in set(dead) - set(names):
                raise ValueError(f"no engine named {d!r} (engines: {', '.join(names)})")
            operative = np.array([[n != d for n in names] for d in dead])
        model = flight_model(self.aircraft, self.aero(config).model, loadings, operative=operative)
        st = model_stabilizer(self.aircraft, model, design_limits, config)
        return trim(
            model,
            tas,
            h,
            kind=kind,
            gamma=gamma,
            bank=bank,
            beta=beta,
            throttle=throttle,
            limits=control_limits(self.aircraft, design_limits, config),
            roles=ROLES,
            stabilizer=st,
            stabilizer_setting=None if st is None else stabilizer,
            initial=initial,
        )

    def modes(self, conditions: Iterable[Condition], throttle: Any = None) -> list[dict[str, Mode] | None]:
        """Modes (short period, phugoid, Dutch roll, roll, spiral) about the straight-flight trim of each
        condition; None where the trim did not converge. ``throttle`` (a scalar or one per condition) fixes the
        throttles: the modes are then those of the steady climb or descent at that thrust (see :meth:`trim`)."""
        from certkit.models.dynamics.modes import (  # deferred: dynamics: `certkit derivatives` builds the aero only
            identify_rows,
        )

        conds = tuple(conditions)

        def compute() -> list[dict[str, Mode] | None]:
            batch = self.trim(conds, throttle=throttle)
            lin = self.linearization(conds, throttle=throttle)
            rows = [i for i, r in enumerate(batch.results) if r.converged]
            found = dict(zip(rows, identify_rows(lin, rows)))
            return [found.get(i) for i in range(len(batch.results))]

        return self.memo(_key("modes", conds, throttle), compute)

    def linearization(self, conditions: Iterable[Condition], throttle: Any = None) -> Linearization:
        """The linearised dynamics (:class:`certkit.models.dynamics.linearize.Linearization`) about the
        straight-flight trim of each condition (at the fixed ``throttle``, see :meth:`modes`), memoised (the one
        :meth:`modes` reads)."""
        from certkit.models.dynamics.linearize import (  # deferred: dynamics: `certkit derivatives` needs the aero only
            linearize,
        )

        conds = tuple(conditions)

        def compute() -> Linearization:
            batch = self.trim(conds, throttle=throttle)
            return linearize(batch.model, batch.x, batch.u)

        return self.memo(_key("linearization", conds, throttle), compute)


def _key(kind: str, conds: tuple[Condition, ...], throttle: Any) -> tuple[Any, ...]:
    """The memo key of conditions' flight points (loading, configuration, altitude, speed) and a fixed throttle."""
    key = (kind,) + tuple((c.mass, c.x_cg, c.configuration, c.altitude, c.speed, c.speed_kind) for c in conds)
    return key if throttle is None else key + ("throttle", _hashable(throttle))


def _number(value: float | None) -> float:
    """A condition's mass or CG, which a flight point needs."""
    if value is None:
        raise ValueError("a flight condition needs its mass and CG")
    return value


def _hashable(value: Any) -> float | tuple[float, ...]:
    arr = np.asarray(value, dtype=float)
    return float(arr) if arr.ndim == 0 else tuple(np.round(arr.ravel(), 9))
