"""Evidence as data: what a rule shows a reviewer, in SI, for :mod:`certkit.report` to draw and format.

A rule's :meth:`~certkit.engine.registry.Rule.evidence` returns :class:`certkit.engine.results.Evidence` items whose
``figure`` is
one of the kinds below and whose ``table`` is a :class:`Table` of typed columns. Nothing here draws: the report
renders each kind with the same conventions (limits and allowables drawn and labelled, critical point marked,
colour bars, colour-blind-safe palette, legends outside the data, aviation units first). Values are SI; an axis or
column names the SI unit of its numbers (``"m/s"``, ``"N·m"``, ``"rad"``) and may ask for a display unit
(``display="kN"``), else the report's default for the unit is used (kn, ft, lb, lbf, deg, kN·m).

Layer: engine (rules build these; the report imports them; this package imports nothing above the models).
"""

from __future__ import annotations

from certkit.engine.evidence.data import (
    Axis,
    Bars,
    Chart,
    Column,
    Heatmap,
    Limit,
    Panel,
    Point,
    Series,
    Table,
    column_for_key,
)

__all__ = ["Axis", "Bars", "Chart", "Column", "Heatmap", "Limit", "Panel", "Point", "Series", "Table", "column_for_key"]
