"""``certkit derivatives``: the derivative table of an aircraft file or an AVL geometry file."""

from __future__ import annotations

import math
from pathlib import Path

from certkit.errors import UserError

VARIABLES = ("alpha", "beta", "p", "q", "r")
COEFFICIENTS = ("CL", "CD", "CY", "Cl", "Cm", "Cn")


def derivative_report(path: str, mach: float | None, alpha_deg: float, beta_deg: float, configuration: str) -> dict:
    from certkit.models.aero.vlm import GeometryError, VortexLattice
    from certkit.models.aero.vlm.avl_file import AvlFileError, read_avl

    model_column = None
    notes: list[str] = []
    try:
        if Path(path).suffix.lower() == ".avl":
            config = read_avl(path)
            source = f"AVL geometry {path}"
            mach = config.mach if mach is None else mach
        else:
            from certkit.aircraft import load_aircraft
            from certkit.context import Context

            ctx = Context(load_aircraft(path))
            if configuration not in ctx.aircraft.configurations:
                raise UserError(f"--config {configuration!r}: not declared (declared: {', '.join(ctx.aircraft.configurations)})")
            from certkit.models.aero.airplane import lattice_configuration

            config = lattice_configuration(ctx.aircraft, configuration)
            source = f"aircraft file {path}, configuration {configuration}"
            mach = 0.2 if mach is None else mach
            aero = ctx.aero(configuration)
            model_column = {name: float(aero.model.derivative(name, mach)) for name in aero.table}
            notes = list(aero.notes) + [f"override {k}: {v['value']} (estimate {v['estimate']})" for k, v in aero.overrides.items()]
        if not 0.0 <= mach < 1.0:
            raise UserError(f"--mach {mach}: the vortex lattice needs 0 <= Mach < 1")
        der = VortexLattice(config, mach=mach).stability_derivatives(alpha=math.radians(alpha_deg), beta=math.radians(beta_deg))
    except (AvlFileError, GeometryError) as exc:
        raise UserError(str(exc)) from None
    sol = der.solution
    ref = config.reference
    lattice = {}
    for coef in COEFFICIENTS:
        for var in VARIABLES:
            lattice[f"{coef}_{var}"] = der[f"{coef}_{var}"]
    for name in config.control_names:
        for coef in COEFFICIENTS:
            lattice[f"{coef}_delta_{name}"] = der[f"{coef}_delta_{name}"]
    report = {
        "source": source, "mach": mach, "alpha_deg": alpha_deg, "beta_deg": beta_deg,
        "conventions": "per radian; stability axes; p̂=pb/2V, q̂=qc/2V, r̂=rb/2V; positive control deflection gives a negative moment",
        "reference": {"area": ref.area, "chord": ref.chord, "span": ref.span, "x_ref": ref.x_ref, "z_ref": ref.z_ref},
        "totals": {"CL": sol.CL, "CD_induced": sol.CD_induced, "span_efficiency": sol.span_efficiency, "CY": sol.CY,
                   "Cl": sol.Cl, "Cm": sol.Cm, "Cn": sol.Cn},
        "neutral_point": der.neutral_point,
        "static_margin": (der.neutral_point - ref.x_ref) / ref.chord,
        "lattice": lattice,
        "notes": notes,
    }
    if model_column is not None:
        report["model"] = {name: model_column.get(name.replace("delta_", ""), float("nan")) for name in lattice}
    return report
