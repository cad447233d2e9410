"""Shared set-ups of the dynamics tests."""

import numpy as np

from certkit.models.dynamics.trim import trim
from certkit.models.flight import ROLES, control_limits, flight_model


def trimmed_baseline(baseline, n: int, speeds: tuple[float, float], altitudes: tuple[float, float], lightest: float):
    """The declared airplane's clean flight model for ``n`` loadings from ``lightest`` × MTOW to MTOW at a 29.5 m CG,
    trimmed in straight flight at speeds (m/s) and altitudes (m) spread over the given ranges: (model, trims)."""
    from certkit.engine.context import Context

    ctx = Context(baseline)
    masses = float(baseline.model.mass.MTOW) * np.linspace(lightest, 1.0, n)
    model = flight_model(baseline.model, ctx.aero("clean").model, [ctx.loading(m, 29.5, "x") for m in masses])
    trims = trim(
        model, np.linspace(*speeds, n), np.linspace(*altitudes, n), limits=control_limits(baseline.model), roles=ROLES
    )
    return model, trims
