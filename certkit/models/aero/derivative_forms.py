"""A declared derivative table turned into the non-dimensional Mach table of
:class:`~certkit.models.aero.derivative_model.StabilityDerivativeModel`.

Speed derivatives (per unit u/u0, Etkin & Reid §4.4) become Mach slopes at the flight condition's Mach M0:
∂C/∂M = C_u / M0, carried by two breakpoints M0 ± ΔM. Dimensional derivatives (stability axes, level flight,
θ0 = 0) are made non-dimensional at the flight condition with K = ½ ρ u0 S = qS/u0, CL = W/(qS) (trimmed, Cm = 0),
CD the declared drag coefficient; from the stability-axis forces X = T − D cos α + L sin α,
Z = −L cos α − D sin α and M about the moment point (Etkin & Reid, Dynamics of Flight, 3rd ed., Table 4.4,
θ0 = 0):

    CL_alpha = −Z_w/K − CD          CD_alpha = CL − X_w/K
    CL_q = −Z_q/(K c/2)             CL_alphadot = −2 u0 Z_wdot/(K c)
    Cm_alpha = M_w/(K c)            Cm_q = M_q/(K c²/2)          Cm_alphadot = 2 u0 M_wdot/(K c²)
    CL_u = −Z_u/K − 2 CL            CD_u = −(X_u − T_u)/K − 2 CD  Cm_u = M_u/(K c)
    CY_beta = Y_v/K   CY_p, CY_r = Y_p, Y_r /(K b/2)   (same for Cl, Cn with K b, K b²/2)
    control terms: CL_δ = −Z_δ/(qS), CD_δ = −X_δ/(qS), CY_δ = Y_δ/(qS), Cl_δ = L_δ/(qSb), Cm_δ = M_δ/(qSc),
    Cn_δ = N_δ/(qSb)

The thrust–speed derivative (T_u, N per m/s, or CT_u = T_u/K) is returned separately for the ideal thrust of a
file without propulsion (:func:`certkit.models.flight.engines`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from certkit.aircraft.derivative_names import SPEED_TERMS

#: half-width of the Mach interval carrying the speed derivatives (the table is linear in Mach)
MACH_HALF_WIDTH = 0.05

_CONTROL_MAP = {
    "X": ("CD", -1.0, "S"),
    "Z": ("CL", -1.0, "S"),
    "Y": ("CY", 1.0, "S"),
    "L": ("Cl", 1.0, "b"),
    "M": ("Cm", 1.0, "c"),
    "N": ("Cn", 1.0, "b"),
}


@dataclass
class NondimensionalTable:
    mach: list[float]
    derivatives: dict[str, float | list[float]]
    controls: list[str]
    thrust_speed: float = 0.0  # ∂T/∂u, N per m/s, for an ideal thrust
    notes: list[str] = field(default_factory=list)


def _dimensional(d: dict, cond, ref, mass: float) -> dict:
    q = cond.dynamic_pressure
    u0, S, b, c = cond.tas, ref.area, ref.span, ref.mean_chord
    K = q * S / u0
    CL = mass * cond.gravity / (q * S)
    CD = float(d["CD0"])
    T_u = float(d.get("T_u", 0.0))
    get = lambda name: float(d.get(name, 0.0))  # noqa: E731
    out = {
        "CL0": CL,
        "CD0": CD,
        "Cm0": 0.0,
        "CL_alpha": -get("Z_w") / K - CD,
        "CD_alpha": CL - get("X_w") / K,
        "CL_q": -get("Z_q") / (K * c / 2),
        "CL_alphadot": -2 * u0 * get("Z_wdot") / (K * c),
        "Cm_alpha": get("M_w") / (K * c),
        "Cm_q": get("M_q") / (K * c * c / 2),
        "Cm_alphadot": 2 * u0 * get("M_wdot") / (K * c * c),
        "CY_beta": get("Y_v") / K,
        "CY_p": get("Y_p") / (K * b / 2),
        "CY_r": get("Y_r") / (K * b / 2),
        "Cl_beta": get("L_v") / (K * b),
        "Cl_p": get("L_p") / (K * b * b / 2),
        "Cl_r": get("L_r") / (K * b * b / 2),
        "Cn_beta": get("N_v") / (K * b),
        "Cn_p": get("N_p") / (K * b * b / 2),
        "Cn_r": get("N_r") / (K * b * b / 2),
    }
    if "Z_u" in d:
        out["CL_u"] = -get("Z_u") / K - 2 * CL
    if "X_u" in d:
        out["CD_u"] = -(get("X_u") - T_u) / K - 2 * CD
    if "M_u" in d:
        out["Cm_u"] = get("M_u") / (K * c)
    if "T_u" in d:
        out["CT_u"] = T_u / K
    lengths = {"S": 1.0, "b": b, "c": c}
    for name, value in d.items():
        prefix, _, control = name.partition("_")
        if (
            prefix in _CONTROL_MAP
            and name not in out
            and name not in ("T_u",)
            and control not in ("u", "v", "w", "p", "q", "r", "wdot")
        ):
            coef, sign, length = _CONTROL_MAP[prefix]
            out[f"{coef}_{control}"] = sign * float(value) / (q * S * lengths[length])
    return out


def nondimensional_table(table, aircraft, cond) -> NondimensionalTable:
    """The table of ``aircraft.aerodynamics.derivative_tables[...]`` as Mach breakpoints and non-dimensional
    derivatives (module docstring); ``cond`` the :class:`~certkit.models.reference_condition.ReferenceCondition`
    (None when the file has no flight condition, then only plain non-dimensional tables are possible)."""
    notes: list[str] = []
    d = dict(table.derivatives)
    if table.form == "dimensional":
        d = _dimensional(d, cond, aircraft.reference, aircraft.mass.MTOW)
        notes.append(
            f"dimensional derivatives made non-dimensional at the flight condition (ρ {cond.density:.4g} "
            f"kg/m³, u0 {cond.tas:.4g} m/s, CL {d['CL0']:.4f} from MTOW × g {cond.gravity:.5g} m/s²)"
        )
    mach = list(table.mach) if table.mach is not None else [cond.mach]
    thrust_speed = 0.0
    if "CT_u" in d:
        thrust_speed = float(d.pop("CT_u")) * cond.dynamic_pressure * aircraft.reference.area / cond.tas
        notes.append(f"thrust–speed derivative ∂T/∂u = {thrust_speed:.4g} N s/m")
    speed = {k: float(d.pop(k)) for k in SPEED_TERMS if k in d}
    if speed:
        m0 = cond.mach
        lo, hi = max(0.0, m0 - MACH_HALF_WIDTH), min(0.99, m0 + MACH_HALF_WIDTH)
        mach = [lo, hi]
        for name, value in speed.items():
            base = name.removesuffix("_u") + "0"  # CL_u → CL0, CD_u → CD0, Cm_u → Cm0
            slope = value / m0
            d[base] = [float(d.get(base, 0.0)) + slope * (m - m0) for m in mach]
        for name, value in list(d.items()):
            if name not in (n.removesuffix("_u") + "0" for n in speed):
                d[name] = [float(value)] * 2 if not isinstance(value, list) else value * 2
        notes.append(
            f"speed derivatives {', '.join(speed)} carried as Mach slopes (C_u / M0, M0 = {m0:.4f}) "
            f"between Mach {lo:.3f} and {hi:.3f}"
        )
    return NondimensionalTable(mach, d, table.control_names, thrust_speed, notes)


def thrust_speed_derivative(aircraft, cond) -> float:
    """∂T/∂u (N per m/s) the derivative tables declare (T_u, or CT_u × ½ρu0S), 0 when none does."""
    for table in aircraft.aerodynamics.derivative_tables.values():
        d = table.derivatives
        if "T_u" in d:
            return float(d["T_u"])
        if "CT_u" in d:
            return float(d["CT_u"]) * cond.dynamic_pressure * aircraft.reference.area / cond.tas
    return 0.0
