"""Vortex-lattice method (own implementation, numpy)."""
