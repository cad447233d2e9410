"""certkit — a compliance engine for transport aircraft against 14 CFR Part 25."""

__version__ = "0.1.0"

from certkit.lean_imports import lazy_f2py

lazy_f2py()
