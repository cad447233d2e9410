"""Vortex-lattice method (own implementation, numpy), AVL-compatible geometry semantics.

Build a :class:`Configuration` of :class:`Surface` objects (by hand, with
:func:`trapezoidal_surface`, or from an AVL file with :func:`read_avl`), then a
:class:`VortexLattice` once, and evaluate it many times (``solve``, ``stability_derivatives``,
``coefficients`` for batches).
"""

from .geometry import (
    CamberLine,
    Configuration,
    ControlSpan,
    ControlSurface,
    GeometryError,
    Section,
    Surface,
    trapezoidal_surface,
)
from .lattice import Lattice, build_lattice
from .solver import FlowSolution, SingularLatticeError, StabilityDerivatives, StripLoads, VortexLattice

__all__ = [
    "CamberLine",
    "Configuration",
    "ControlSpan",
    "ControlSurface",
    "FlowSolution",
    "GeometryError",
    "Lattice",
    "Section",
    "SingularLatticeError",
    "StabilityDerivatives",
    "StripLoads",
    "Surface",
    "VortexLattice",
    "build_lattice",
    "trapezoidal_surface",
]
