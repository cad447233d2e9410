"""``certkit derivatives``: the derivative table of an aircraft file or an AVL geometry file."""

from __future__ import annotations

import math
from pathlib import Path

from certkit.conventions import CONTROL_SIGNS, DRAG_AXIS, INDUCED_DRAG
from certkit.errors import UserError
from certkit.models.aero.vlm import GeometryError, VortexLattice
from certkit.models.aero.vlm.avl_file import AvlFileError, read_avl

VARIABLES = ("alpha", "beta", "p", "q", "r")
COEFFICIENTS = ("CL", "CD", "CY", "Cl", "Cm", "Cn")


def derivative_report(path: str, mach: float | None, alpha_deg: float, beta_deg: float, configuration: str) -> dict:
    model_column = None
    model_point = None
    notes: list[str] = []
    hidden: tuple[str, ...] = ()  # lattice controls that are not the flight model's
    kind = "avl" if Path(path).suffix.lower() == ".avl" else "aircraft"
    try:
        if kind == "avl":
            config = read_avl(path)
            source = f"AVL geometry {path}"
            mach = config.mach if mach is None else mach
        else:
            from certkit.aircraft import load_aircraft  # deferred: an .avl run loads no pint, scipy, numba
            from certkit.engine.context import Context  # deferred: an .avl run loads no pint, scipy, numba

            ctx = Context(load_aircraft(path))
            if configuration not in ctx.aircraft.configurations:
                raise UserError(
                    f"--config {configuration!r}: not declared (declared: {', '.join(ctx.aircraft.configurations)})"
                )
            from certkit.models.aero.airplane import (  # deferred: an .avl run loads no pint, scipy, numba
                FLAP_CONTROL,
                lattice_configuration,
            )

            hidden = (FLAP_CONTROL,)  # the airplane's lattice carries the wing flap for the strip loads only

            source = f"aircraft file {path}, configuration {configuration}"
            if mach is None:
                from certkit.models.reference_condition import (  # deferred: an .avl run loads no pint, scipy, numba
                    reference_condition,
                )

                cond = reference_condition(ctx.aircraft)
                mach = 0.2 if cond is None else cond.mach
            aero = ctx.aero(configuration)
            model_column = {name: float(aero.model.derivative(name, mach)) for name in aero.table}
            model_point = _model_neutral_point(model_column, ctx.aircraft.reference)
            notes = list(aero.notes) + [
                f"override {k}: {v['value']} (estimate {v['estimate']})" for k, v in aero.overrides.items()
            ]
            if ctx.aircraft.geometry is None:  # a derivative-table airplane: its table is all there is
                return _model_only(
                    source, mach, alpha_deg, beta_deg, ctx.aircraft.reference, model_column, model_point, notes
                )
            config = lattice_configuration(ctx.aircraft, configuration, flap=True)  # the model's own lattice
        if not 0.0 <= mach < 1.0:
            raise UserError(f"--mach {mach}: the vortex lattice needs 0 <= Mach < 1")
        der = VortexLattice(config, mach=mach).stability_derivatives(
            alpha=math.radians(alpha_deg), beta=math.radians(beta_deg)
        )
    except (AvlFileError, GeometryError) as exc:
        raise UserError(str(exc)) from None
    sol = der.solution
    ref = config.reference
    lattice = {}
    for coef in COEFFICIENTS:
        for var in VARIABLES:
            lattice[f"{coef}_{var}"] = der[f"{coef}_{var}"]
    for name in (n for n in config.control_names if n not in hidden):
        for coef in COEFFICIENTS:
            lattice[f"{coef}_delta_{name}"] = der[f"{coef}_delta_{name}"]
    lattice_np = der.neutral_point
    report = {
        "source": source,
        "input_kind": kind,
        "mach": mach,
        "alpha_deg": alpha_deg,
        "beta_deg": beta_deg,
        "conventions": _conventions(kind),
        "reference": {"area": ref.area, "chord": ref.chord, "span": ref.span, "x_ref": ref.x_ref, "z_ref": ref.z_ref},
        "totals": {
            "CL": sol.CL,
            "CD_induced_trefftz": sol.CD_induced,
            "span_efficiency": sol.span_efficiency,
            "CY": sol.CY,
            "Cl": sol.Cl,
            "Cm": sol.Cm,
            "Cn": sol.Cn,
        },
        "induced_drag_method": INDUCED_DRAG,
        "neutral_point": lattice_np if model_point is None else model_point,
        "static_margin": ((lattice_np if model_point is None else model_point) - ref.x_ref) / ref.chord,
        "neutral_point_source": (
            "vortex lattice"
            if model_point is None
            else "model: lattice + fuselage term + overrides, x_ref − c̄ Cm_alpha/CL_alpha"
        ),
        "lattice_neutral_point": lattice_np,
        "lattice_static_margin": (lattice_np - ref.x_ref) / ref.chord,
        "lattice": lattice,
        "notes": notes,
    }
    if model_column is not None:  # a term the model does not carry is None (JSON null), not NaN
        report["model"] = {name: model_column.get(name.replace("delta_", "")) for name in lattice}
    return report


def _conventions(kind: str) -> dict:
    return {
        "axes": "per radian; stability axes; p̂=pb/2V, q̂=qc/2V, r̂=rb/2V",
        "controls": CONTROL_SIGNS[kind],
        "drag": DRAG_AXIS,
    }


def _model_only(source, mach, alpha_deg, beta_deg, reference, model, model_point, notes) -> dict:
    """The report of an aircraft file without geometry: the declared table (made non-dimensional), no lattice."""
    return {
        "source": source,
        "input_kind": "aircraft",
        "mach": mach,
        "alpha_deg": alpha_deg,
        "beta_deg": beta_deg,
        "conventions": _conventions("aircraft"),
        "reference": {
            "area": reference.area,
            "chord": reference.mean_chord,
            "span": reference.span,
            "x_ref": reference.moment_point.x,
            "z_ref": reference.moment_point.z,
        },
        "totals": None,
        "induced_drag_method": None,
        "neutral_point": model_point,
        "static_margin": None
        if model_point is None
        else (model_point - reference.moment_point.x) / reference.mean_chord,
        "neutral_point_source": "model: the declared derivative table, x_ref − c̄ Cm_alpha/CL_alpha",
        "lattice_neutral_point": None,
        "lattice_static_margin": None,
        "lattice": None,
        "model": model,
        "notes": notes
        + ["no geometry: no vortex lattice; the declared table at this Mach (α and β do not enter a linear table)"],
    }


def _model_neutral_point(model: dict, reference) -> float | None:
    """The stick-fixed neutral point of the model's derivatives: where Cm_alpha vanishes, x_ref − c̄ Cm_α/CL_α
    (Etkin & Reid eq. 2.3,24 with the moment point at x_ref)."""
    cla, cma = model.get("CL_alpha"), model.get("Cm_alpha")
    if not cla:
        return None
    return reference.moment_point.x - reference.mean_chord * cma / cla
