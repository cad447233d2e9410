"""The derivative names an aircraft file's ``aerodynamics.derivative_tables`` accepts, with meaning and unit.

Two forms (``form:`` of a table):

``nondimensional`` (default) — coefficients and their derivatives per radian, stability axes, rates per
p̂ = pb/2V, q̂ = qc̄/2V, r̂ = rb/2V, α̇ per α̇c̄/2V (AVL and Etkin & Reid's normalisation); speed derivatives per
unit u/u0 at the table's flight condition (Etkin & Reid's C_Lu = ∂C_L/∂(u/u0)).

``dimensional`` — the forces and moments per unit of the motion variable, SI, stability axes at the flight
condition, level flight (θ0 = 0), as Etkin & Reid (Table 4.4 form: X_u, Z_w, M_q, ...), NASA and ESDU publish
them: N per m/s, N per m/s², N per rad/s (N·m for moments), N or N·m per rad for the controls.

A control term is ``<prefix>_<control>``: non-dimensional prefixes CL, CD, CY, Cl, Cm, Cn (per rad), dimensional
X, Y, Z, L, M, N (N or N·m per rad). Signs of control deflections: :mod:`certkit.conventions`.
"""

from __future__ import annotations

#: non-dimensional derivative name → (meaning, unit)
NONDIMENSIONAL: dict[str, tuple[str, str]] = {
    "CL0": ("lift coefficient at zero angle of attack (controls neutral)", "1"),
    "CL_alpha": ("lift-curve slope ∂CL/∂α", "1/rad"),
    "CL_q": ("∂CL/∂q̂, q̂ = q c̄ / 2V", "1"),
    "CL_alphadot": ("∂CL/∂(α̇ c̄ / 2V)", "1"),
    "CL_u": ("speed derivative ∂CL/∂(u/u0) at the flight condition", "1"),
    "CD0": ("drag coefficient at zero lift (or the parabolic polar's minimum)", "1"),
    "k": ("induced-drag factor of the polar CD = CD0 + k (CL − CL_minD)²", "1"),
    "CL_minD": ("lift coefficient of minimum drag", "1"),
    "CD_alpha": ("∂CD/∂α", "1/rad"),
    "CD_alpha2": ("½ ∂²CD/∂α² (the α² term)", "1/rad²"),
    "CD_u": ("speed derivative ∂CD/∂(u/u0) at the flight condition", "1"),
    "CT_u": ("thrust–speed derivative (u0 / q S) ∂T/∂u at the flight condition (files without propulsion)", "1"),
    "CY_beta": ("∂CY/∂β", "1/rad"),
    "CY_p": ("∂CY/∂p̂, p̂ = p b / 2V", "1"),
    "CY_r": ("∂CY/∂r̂, r̂ = r b / 2V", "1"),
    "Cl_beta": ("rolling-moment derivative ∂Cl/∂β (dihedral effect)", "1/rad"),
    "Cl_p": ("roll damping ∂Cl/∂p̂", "1"),
    "Cl_r": ("∂Cl/∂r̂", "1"),
    "Cm0": ("pitching-moment coefficient at zero angle of attack about the moment point", "1"),
    "Cm_alpha": ("∂Cm/∂α about the moment point", "1/rad"),
    "Cm_q": ("pitch damping ∂Cm/∂q̂", "1"),
    "Cm_alphadot": ("∂Cm/∂(α̇ c̄ / 2V)", "1"),
    "Cm_u": ("speed derivative ∂Cm/∂(u/u0) at the flight condition", "1"),
    "Cn_beta": ("weathercock stability ∂Cn/∂β", "1/rad"),
    "Cn_p": ("∂Cn/∂p̂", "1"),
    "Cn_r": ("yaw damping ∂Cn/∂r̂", "1"),
}

#: speed derivatives: converted to a Mach slope at the flight condition (C_M = C_u / M0)
SPEED_TERMS = ("CL_u", "CD_u", "Cm_u")

#: dimensional derivative name → (meaning, unit)
DIMENSIONAL: dict[str, tuple[str, str]] = {
    "X_u": ("∂X/∂u, X the stability-axis force along x (thrust effects included unless T_u is given)", "N s/m"),
    "X_w": ("∂X/∂w", "N s/m"),
    "Z_u": ("∂Z/∂u, Z along the stability z axis (down)", "N s/m"),
    "Z_w": ("∂Z/∂w", "N s/m"),
    "Z_q": ("∂Z/∂q", "N s/rad"),
    "Z_wdot": ("∂Z/∂ẇ", "N s²/m"),
    "M_u": ("∂M/∂u, M the pitching moment", "N m s/m"),
    "M_w": ("∂M/∂w", "N m s/m"),
    "M_q": ("∂M/∂q", "N m s/rad"),
    "M_wdot": ("∂M/∂ẇ", "N m s²/m"),
    "Y_v": ("∂Y/∂v, Y the side force", "N s/m"),
    "Y_p": ("∂Y/∂p", "N s/rad"),
    "Y_r": ("∂Y/∂r", "N s/rad"),
    "L_v": ("∂L/∂v, L the rolling moment (stability axes)", "N m s/m"),
    "L_p": ("∂L/∂p", "N m s/rad"),
    "L_r": ("∂L/∂r", "N m s/rad"),
    "N_v": ("∂N/∂v, N the yawing moment (stability axes)", "N m s/m"),
    "N_p": ("∂N/∂p", "N m s/rad"),
    "N_r": ("∂N/∂r", "N m s/rad"),
    "T_u": ("thrust–speed derivative ∂T/∂u (files without propulsion; then X_u excludes it)", "N s/m"),
    "CD0": ("drag coefficient in the flight condition (non-dimensional; needed to recover CL_alpha from Z_w)", "1"),
}

NONDIMENSIONAL_CONTROL = {
    "CL": "lift",
    "CD": "drag",
    "CY": "side-force",
    "Cl": "rolling-moment",
    "Cm": "pitching-moment",
    "Cn": "yawing-moment",
}
DIMENSIONAL_CONTROL = {
    "X": ("x force", "N/rad"),
    "Y": ("side force", "N/rad"),
    "Z": ("z force", "N/rad"),
    "L": ("rolling moment", "N m/rad"),
    "M": ("pitching moment", "N m/rad"),
    "N": ("yawing moment", "N m/rad"),
}
#: control names a table may use without listing them in ``controls:`` (others must be listed, so that a misspelt
#: derivative such as X_uu is an error, not a control named "uu")
#: the control of a movable horizontal stabiliser in the flight models (deflection from the declared tail incidence)
STABILIZER = "stabilizer"
USUAL_CONTROLS = ("elevator", "aileron", "rudder", "stabilizer", "spoiler", "flap", "slat")
_MOTION = ("alpha", "beta", "p", "q", "r", "u", "v", "w", "wdot", "alphadot", "minD")


def control_term(name: str, form: str) -> tuple[str, str] | None:
    """(prefix, control) when ``name`` is a control term of the form, else None."""
    prefix, _, control = name.partition("_")
    prefixes = NONDIMENSIONAL_CONTROL if form == "nondimensional" else DIMENSIONAL_CONTROL
    if prefix in prefixes and control and control not in _MOTION:
        return prefix, control
    return None


def unknown_names(names, form: str, controls) -> list[str]:
    """The names a table of ``form`` does not accept (misspelt, of the other form, or of an undeclared control)."""
    known = NONDIMENSIONAL if form == "nondimensional" else DIMENSIONAL
    out = []
    for name in names:
        if name in known:
            continue
        term = control_term(name, form)
        if term is None or term[1] not in controls:
            out.append(name)
    return out


def schema_description() -> str:
    """Every accepted name with its meaning and unit, for ``certkit schema``."""
    lines = ["Non-dimensional form (form: nondimensional):"]
    lines += [f"  {n}: {m} [{u}]" for n, (m, u) in NONDIMENSIONAL.items()]
    lines += [
        "  <CL|CD|CY|Cl|Cm|Cn>_<control>: control derivative per rad (e.g. Cm_elevator)",
        "Dimensional form (form: dimensional; SI, stability axes at the flight condition):",
    ]
    lines += [f"  {n}: {m} [{u}]" for n, (m, u) in DIMENSIONAL.items()]
    lines += ["  <X|Y|Z|L|M|N>_<control>: control derivative, N/rad or N m/rad (e.g. M_elevator)"]
    return "\n".join(lines)


def schema_properties() -> dict:
    """JSON-Schema properties (name → description) of both forms, so that an editor completes them."""
    props = {}
    for table in (NONDIMENSIONAL, DIMENSIONAL):
        for name, (meaning, unit) in table.items():
            props[name] = {
                "anyOf": [{"type": "number"}, {"type": "array", "items": {"type": "number"}}],
                "description": f"{meaning} [{unit}]",
            }
    return props
