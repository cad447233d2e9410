"""Regulation content shared by the Subpart B climb and controllability rules (no rule here): the CG positions their
conditions are evaluated at (§25.121, §25.143, §25.147)."""

from __future__ import annotations

#: the CG positions of the design-weight conditions: the envelope's forward and aft limits and the reference CG
CGS = ("forward", "reference", "aft")
