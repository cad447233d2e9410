"""The C_N,max criterion of the manoeuvring envelope's stall lines, shared by §25.333, §25.335(c)/(d) and the
§25.331(b) balanced manoeuvres (regulation content, no rule here)."""

from __future__ import annotations

from certkit.engine.registry import Criterion

CN_SOURCE = (
    "14 CFR 25.335(c)/(d) and 25.333: estimated VS0/VS1 must be conservative, so C_Nmax = C_Lmax (factor 1) "
    "unless the aircraft file's criteria override declares a larger factor with its justification"
)
CN_OVER_CL = {
    "cn_over_cl": Criterion(
        1.0,
        "",
        CN_SOURCE,
        "C_Nmax / C_Lmax of the stall lines and VS1 (1: the declared 1-g CLmax; a larger value needs a justification)",
    )
}
