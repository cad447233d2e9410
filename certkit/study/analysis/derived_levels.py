"""Handling-quality levels derived from surrogates of the mode quantities, not regressed.

A design record gives, per mode, CG corner and configuration, the MIL-F-8785C level
(``level.<mode>.<corner>.<configuration>``, an integer, the worst over the conditions), the quantities of the
condition that sets it (``mode.<mode>.<quantity>.…``: damping ratio, natural frequency, the short period's control
anticipation parameter) and the least level margins over the conditions (``mode.<mode>.level<L>_margin.…``, L = 1,
2, 3: ≥ 0 exactly where every condition is Level L or better). An integer is a poor thing to regress: the level is
derived from surrogates of the margins — continuous where the condition that sets the level changes, as the
quantities of that condition are not — or, in stores without them, as the rule's own function of the quantities'
surrogates (:class:`certkit.engine.registry.ModeResponses` ``level``). The margins (or ``level_margin`` of the
quantities) let the optimiser hold a level as an inequality. How well it works is measured, not assumed: the derived
level is compared with the recorded one on the validation cases (held out from every fit), and the rule's function
is checked to reproduce every recorded level from the recorded quantities.

A level response keeps a regressed surrogate only where its quantities are not recorded or cannot be fitted (stores
of older records); the report says which.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from certkit.design.record import MODE_QUANTITIES
from certkit.engine.registry import DiscoveryOptions, ModeResponses, discover
from certkit.study.analysis.cases import Cases
from certkit.study.analysis.surrogates import Fit, Surrogate, fit_all
from certkit.study.spec import LEVEL_PREFIX, Study

#: the level function's keyword → the record's mode quantity (``mode.<mode>.<quantity>.…``); the control
#: anticipation parameter only where recorded (the short period)
LEVEL_INPUTS = {"zeta": "zeta", "wn": "wn_rad_s", "cap": "cap"}
assert set(LEVEL_INPUTS.values()) <= set(MODE_QUANTITIES)
#: the level margin is clipped to ±this (a relative distance to a boundary: ten times the bound says nothing more,
#: and an optimiser's finite differences need finite values where a quantity is unbounded)
MARGIN_CLIP = 10.0


@dataclass(frozen=True)
class LevelSource:
    """Where a level response comes from: the mode, the configuration, the quantity responses per keyword of the
    level function, and the rule's offer that holds the function."""

    response: str
    mode: str
    configuration: str
    sources: dict[str, str]
    offer: ModeResponses
    #: "margins": the least level margins over the conditions (sources keyed "1", "2", "3"); "quantities": ζ, ω_n, CAP
    kind: str = "quantities"


@dataclass(frozen=True)
class _Label:
    label: str


@dataclass
class DerivedLevel:
    """A level predicted as the rule's function of the quantities' surrogates; the analysis uses it where it would
    use a surrogate (``predict``, ``flagged``), and the optimiser its ``level_margin``."""

    source: LevelSource
    quantities: dict[str, Surrogate]
    threshold: float
    n_validation: int = 0
    n_agree: int = 0
    n_recorded: int = 0
    n_reproduced: int = 0
    plot_data: dict[str, Any] = field(default_factory=dict, repr=False)
    cv: Fit = field(default_factory=lambda: Fit(0, None, None, None))

    @property
    def response(self) -> str:
        return self.source.response

    @property
    def kept(self) -> _Label:
        names = ", ".join(self.source.sources.values())
        return _Label(f"MIL-F-8785C level of the surrogates of {names}")

    @property
    def agreement(self) -> float | None:
        """Fraction of the validation cases whose derived level equals the recorded one."""
        return self.n_agree / self.n_validation if self.n_validation else None

    @property
    def flagged(self) -> bool:
        a = self.agreement
        return a is None or a < self.threshold or any(s.flagged for s in self.quantities.values())

    def _q(self, x: np.ndarray) -> dict[str, np.ndarray]:
        return {kw: s.predict(x) for kw, s in self.quantities.items()}

    def predict(self, x: np.ndarray) -> np.ndarray:
        s = self.source
        if s.kind == "margins":
            return level_of_margins(self._q(x))
        return np.asarray(s.offer.level(s.mode, s.configuration, **self._q(x)), dtype=float).ravel()

    def level_margin(self, x: np.ndarray, level: int) -> np.ndarray:
        """≥ 0 where the predicted level is ``level`` or better (clipped to ±:data:`MARGIN_CLIP`)."""
        s = self.source
        if s.kind == "margins":
            x = np.atleast_2d(x)
            if level >= 4:
                return np.full(len(x), MARGIN_CLIP)
            return np.clip(self.quantities[str(level)].predict(x), -MARGIN_CLIP, MARGIN_CLIP)
        m = s.offer.level_margin(s.mode, s.configuration, int(level), **self._q(x))
        return np.clip(np.asarray(m, dtype=float).ravel(), -MARGIN_CLIP, MARGIN_CLIP)


def level_of_margins(margins: dict[str, np.ndarray]) -> np.ndarray:
    """The level from the least level margins {"1": m₁, "2": m₂, "3": m₃}: the best L with m_L ≥ 0, else 4."""
    m1, m2, m3 = (np.asarray(margins[k], dtype=float).ravel() for k in ("1", "2", "3"))
    return np.where(m1 >= 0, 1.0, np.where(m2 >= 0, 2.0, np.where(m3 >= 0, 3.0, 4.0)))


def mode_offers(rules: list[Any] | None = None) -> dict[str, ModeResponses]:
    """Mode → the first rule offer that gives its level from the quantities (the discovered rules by default)."""
    out: dict[str, ModeResponses] = {}
    for r in discover(DiscoveryOptions()) if rules is None else rules:
        for offer in getattr(r, "offers", ()):
            if isinstance(offer, ModeResponses) and offer.level is not None and offer.level_margin is not None:
                for mode in offer.modes:
                    out.setdefault(mode, offer)
    return out


def _recorded(cases: Cases, response: str) -> bool:
    column = cases.frame.get("resp:" + response)
    return column is not None and bool(np.isfinite(column.to_numpy(dtype=float)).any())


def level_sources(study: Study, cases: Cases, offers: dict[str, ModeResponses]) -> dict[str, LevelSource]:
    """The analysed level responses whose least level margins (or else damping ratio and natural frequency) the store
    records, and whose mode a rule gives the level function of, with the responses they come from."""
    out = {}
    for name in study.analysed_responses():
        parts = name.split(".")
        if not name.startswith(LEVEL_PREFIX) or len(parts) != 4 or parts[1] not in offers:
            continue
        _, mode, corner, configuration = parts
        margins = {str(lv): f"mode.{mode}.level{lv}_margin.{corner}.{configuration}" for lv in (1, 2, 3)}
        if all(_recorded(cases, r) for r in margins.values()):
            out[name] = LevelSource(name, mode, configuration, margins, offers[mode], "margins")
            continue
        sources = {kw: f"mode.{mode}.{q}.{corner}.{configuration}" for kw, q in LEVEL_INPUTS.items()}
        sources = {kw: r for kw, r in sources.items() if _recorded(cases, r)}
        if "zeta" in sources and "wn" in sources:
            out[name] = LevelSource(name, mode, configuration, sources, offers[mode])
    return out


def _rows(cases: Cases, role: str, names: list[str]) -> tuple[np.ndarray, np.ndarray]:
    rows = cases.rows(role)
    cols = ["resp:" + n for n in names]
    if any(c not in rows.columns for c in cols):
        return np.empty((0, len(cases.x_columns))), np.empty((0, len(names)))
    values = rows[cols].to_numpy(dtype=float)
    keep = np.all(np.isfinite(values), axis=1)
    return rows[list(cases.x_columns)].to_numpy(dtype=float)[keep], values[keep]


def derive(source: LevelSource, quantities: dict[str, Surrogate], cases: Cases, threshold: float) -> DerivedLevel:
    """The derived level of ``source`` with its agreement with the recorded levels (validation cases) and the check
    that the rule's function reproduces each recorded level from the recorded quantities (every ok case)."""
    kws = list(source.sources)
    names = [source.response] + [source.sources[k] for k in kws]
    d = DerivedLevel(source, quantities, threshold)
    x_val, v_val = _rows(cases, "validation", names)
    if len(x_val):
        d.n_validation = len(x_val)
        d.n_agree = int(np.sum(d.predict(x_val) == v_val[:, 0]))
    recorded = [_rows(cases, role, names)[1] for role in ("training", "validation")]
    values = np.vstack(recorded)
    if len(values):
        q = {k: values[:, i + 1] for i, k in enumerate(kws)}
        again = (
            level_of_margins(q)
            if source.kind == "margins"
            else np.asarray(source.offer.level(source.mode, source.configuration, **q), dtype=float).ravel()
        )
        d.n_recorded, d.n_reproduced = len(values), int(np.sum(again == values[:, 0]))
    train = _rows(cases, "training", [source.response])[1]
    d.plot_data = {"train": (train[:, 0] if len(train) else np.empty(0),)}
    return d


def fit_predictors(
    study: Study,
    cases: Cases,
    log: Callable[[str], object] = lambda msg: None,
    offers: dict[str, ModeResponses] | None = None,
) -> tuple[dict[str, Surrogate], dict[str, DerivedLevel], dict[str, str]]:
    """(surrogates of the analysed responses and of the mode quantities the levels need, the derived levels, the
    reasons of the responses nothing could be fitted for). A level whose quantities could not be fitted is
    regressed instead (:func:`~certkit.study.analysis.surrogates.fit_all`); ``{**surrogates, **levels}`` is what
    the Monte Carlo, the optimiser and the checks predict with."""
    plan = level_sources(study, cases, mode_offers() if offers is None else offers)
    quantity_names = [r for s in plan.values() for r in s.sources.values()]
    names = [n for n in study.analysed_responses() if n not in plan] + quantity_names
    surrogates, not_fitted = fit_all(study, cases, log, names=list(dict.fromkeys(names)))
    levels: dict[str, DerivedLevel] = {}
    regress = []
    for name, source in plan.items():
        if all(r in surrogates for r in source.sources.values()):
            quantities = {kw: surrogates[r] for kw, r in source.sources.items()}
            levels[name] = derive(source, quantities, cases, study.analysis.r2_threshold)
            log(f"level {name}: derived from {', '.join(source.sources.values())}")
        else:
            regress.append(name)
    if regress:
        more, more_not = fit_all(study, cases, log, names=regress)
        surrogates.update(more)
        not_fitted.update(more_not)
    return surrogates, levels, not_fitted
