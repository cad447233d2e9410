"""Design studies: many design evaluations over a design of experiments, and their analysis."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from certkit.study.analysis.surrogate_file import SurrogateSet


def load_surrogates(path: str | Path) -> SurrogateSet:
    """The surrogates written by ``certkit study export --surrogates FILE``: a
    :class:`certkit.study.analysis.surrogate_file.SurrogateSet` with ``predict(points)`` (designs as rows in SI or
    mappings {variable path: value}) and ``possible(points)`` (the possible-design classifier)."""
    from certkit.study.analysis.surrogate_file import (  # deferred: scikit-learn only when surrogates are loaded
        load_surrogates as load,
    )

    return load(path)
