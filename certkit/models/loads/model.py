"""Strip loads model of the lifting surfaces: aerodynamic and inertial loads integrated along the span.

Each lifting surface (one half of the wing and of the horizontal tail, the whole fin) is cut into the
spanwise strips of the vortex lattice (:class:`certkit.models.aero.vlm.VortexLattice`). For every strip
the model keeps, per unit dynamic pressure,

* the normal force of each **unit lattice solution** — the base state (α = 0, incidence and camber),
  α, β, the body rates p̂ = pb/2V, q̂ = qc/2V, r̂ = rb/2V and each control deflection — obtained by
  central differences of the lattice's (quadratic) force about the base state, at each Mach
  breakpoint of the airplane model and interpolated linearly in Mach as the airplane model is;
* the X position where that force acts: the circulation-weighted position of the strip's bound
  vortices for the same unit solution (the first-order Kutta–Joukowski force of each bound leg is
  proportional to its circulation).

Loads at an instant are the superposition  N_j = q̄ Σ_k x_k N_jk(M)  over the inputs x_k (linear, so a
whole batch of conditions and time steps is one tensor contraction), plus the inertial force of the
strip's mass m_j at its station, −m_j g n_local with the rigid-body load factor at the strip,
n_z,loc = n_z + q̇ (X_cg − X_j)/g − ṗ Y_j/g and n_y,loc = n_y + (ṙ (X_cg − X_j) − ṗ (Z_cg − Z_j))/g
(body-axis angular accelerations; the roll-acceleration term ṗ Y_j is the inertia relief of a rolling
wing or tail, §25.349; centripetal terms neglected).

Sign conventions (airplane frame X aft, Y right, Z up): the surface normal points up for the wing and
horizontal tail and to the right (+Y) for the fin. At each station, for the part of the surface
outboard of it: **shear** = Σ normal force (N); **bending** = Σ normal force × distance along the span in
the plane of the surface (N·m, positive when an upward/rightward load bends the tip up/right);
**torsion** about the reference axis at ``axis_fraction`` of the local chord, streamwise
(N·m, positive nose up / leading edge toward the positive normal): Σ N (X_axis − X_load).

Strip mass: the structural mass of the surface (aircraft-file component named like the surface,
group ``structure``) distributed in proportion to strip area at ``axis_fraction`` of the chord; on
the wing the propulsion components (engines, nacelles) are point masses at their span station. Wing
fuel is kept apart: one inertial table per declared tank and per kilogram of its fuel (the tank spread on
the strips by :mod:`certkit.models.loads.fuel`), so that any fuel state is a linear combination
(:meth:`SurfaceLoads.fuel_loads`); the station loads without a fuel state carry no fuel.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from certkit.models.loads.fuel import wing_tank_shares
from certkit.units import G0

QUANTITIES = ("shear", "bending", "torsion")
#: a strip's force per unit circulation from the lattice is kept within this band of the freestream Kutta–Joukowski
#: value (2 × strip width per unit q̄); outside it the quotient of two small differences is not the strip's
RATIO_BAND = (0.2, 5.0)
UNITS = {"shear": "N", "bending": "N·m", "torsion": "N·m"}
RATE_INPUTS = ("alpha", "beta", "p_hat", "q_hat", "r_hat")
#: structural component names that carry each surface's mass
SURFACE_COMPONENTS = {
    "wing": ("wing",),
    "horizontal_tail": ("horizontal tail", "horizontal_tail", "stabilizer", "stabiliser"),
    "vertical_tail": ("vertical tail", "vertical_tail", "fin"),
}
#: terms of the inertial force, see :meth:`SurfaceLoads.inertia_terms`
INERTIA_TERMS = ("n_z", "qdot_xcg", "qdot", "n_y", "rdot_xcg", "rdot", "pdot_zcg", "pdot")
EPS = 1e-3


@dataclass
class SurfaceLoads:
    """Strips and load stations of one surface, with the unit load tables.

    ``aero[m, k, q, s]``: load quantity q at station s per unit dynamic pressure and unit input k
    (``inputs``) at Mach breakpoint m; ``inertia[t, q, s]``: per unit inertial term t (INERTIA_TERMS).
    ``strip_aero[m, k, j]``: normal force per unit q̄ of strip j (for span-load plots)."""

    name: str
    inputs: tuple[str, ...]
    mach: np.ndarray
    station_names: tuple[str, ...]
    station_span: np.ndarray  # m, along the span in the plane of the surface from the root
    station_y: np.ndarray  # m, airplane Y (Z for the fin) of each station
    strip_span: np.ndarray
    strip_x: np.ndarray  # X of the reference axis at each strip (m)
    strip_mass: np.ndarray  # kg
    aero: np.ndarray
    inertia: np.ndarray
    strip_aero: np.ndarray
    axis_fraction: float
    notes: list[str] = field(default_factory=list)
    #: declared fuel tanks (all, in the aircraft file's order) and the inertial loads per kilogram of each one's fuel,
    #: ``fuel_inertia[k, t, q, s]`` (zero for a tank this half does not carry); empty for a surface without tanks
    tank_names: tuple[str, ...] = ()
    fuel_inertia: np.ndarray | None = None
    fuel_strip_share: np.ndarray | None = None  # (K, J) fraction of each tank's fuel on each strip
    #: ``vertical_force[m, k]``: the surface's force along airplane Z (lift) per unit q̄ and unit input k at Mach
    #: breakpoint m (the strips' normal forces times the Z component of their normals; zero for the fin)
    vertical_force: np.ndarray | None = None
    #: m, the surface's mean aerodynamic chord Σ c² Δs / Σ c Δs over its strips (the gust penetration lag's chord)
    mean_chord: float = float("nan")

    @property
    def structural_mass(self) -> float:
        return float(self.strip_mass.sum())

    @functools.cached_property
    def top_mach(self) -> float:
        """The highest Mach breakpoint of the unit tables (beyond it they are held, not computed)."""
        return float(np.max(self.mach))

    def input_for_lift(self, name: str, lift_per_qbar, mach) -> np.ndarray:
        """The value of input ``name`` whose force along airplane Z on this surface is ``lift_per_qbar`` (m², per unit
        q̄; arrays broadcast with ``mach``), the unit tables interpolated in Mach as :meth:`aero_loads` does."""
        k = self.inputs.index(name)
        i, w = self._mach_weights(mach)
        table = self.vertical_force[:, k]
        per_unit = table[i] * (1 - w) + table[np.minimum(i + 1, table.size - 1)] * w
        return np.asarray(lift_per_qbar, dtype=float) / per_unit

    def _mach_weights(self, mach):
        m = self.mach
        x = np.clip(np.asarray(mach, dtype=float), m[0], m[-1])
        i = np.clip(np.searchsorted(m, x, side="right") - 1, 0, max(m.size - 2, 0))
        if m.size == 1:
            return i, np.zeros_like(x)
        return i, (x - m[i]) / (m[i + 1] - m[i])

    def _superpose(self, qbar, mach, inputs, table) -> np.ndarray:
        """q̄ Σ_k x_k T_k(M), linear in Mach between the two breakpoints around each point (as the airplane model
        interpolates), over the inputs given (the others are zero; ``one`` is implied)."""
        qbar = np.asarray(qbar, dtype=float)
        i, w = self._mach_weights(mach)
        shape = np.broadcast_shapes(
            qbar.shape, np.shape(i), *(np.shape(inputs[n]) for n in self.inputs[1:] if n in inputs)
        )
        cols = [0] + [k for k, name in enumerate(self.inputs[1:], start=1) if name in inputs]
        x = np.empty((len(cols), int(np.prod(shape, dtype=int))))
        x[0] = 1.0
        for r, k in enumerate(cols[1:], start=1):
            x[r] = np.broadcast_to(np.asarray(inputs[self.inputs[k]], dtype=float), shape).ravel()
        flat = np.ascontiguousarray(table.reshape(table.shape[0], table.shape[1], -1))
        out = np.empty((x.shape[1], flat.shape[2]))
        # fresh writable copies whatever the shapes (a broadcast view would be read-only: another kernel signature)
        _superpose_kernel(
            np.array(np.broadcast_to(qbar, shape).ravel(), dtype=float),
            np.array(np.broadcast_to(i, shape).ravel(), dtype=np.int64),
            np.array(np.broadcast_to(w, shape).ravel(), dtype=float),
            x,
            np.array(cols, dtype=np.int64),
            flat,
            out,
        )
        return out.reshape(shape + table.shape[2:])

    def aero_loads(self, qbar, mach, inputs: dict[str, np.ndarray]) -> np.ndarray:
        """Aerodynamic station loads (..., 3, n_stations) for arrays of q̄, Mach and the named inputs
        (missing inputs are zero; ``one`` is implied)."""
        return self._superpose(qbar, mach, inputs, self.aero)

    def inertia_loads(self, terms: dict[str, np.ndarray]) -> np.ndarray:
        """Inertial station loads (..., 3, n_stations) from the named inertial terms (INERTIA_TERMS)."""
        present = [(t, np.asarray(terms[name], dtype=float)) for t, name in enumerate(INERTIA_TERMS) if name in terms]
        if not present:
            return np.zeros(self.inertia.shape[1:])
        shape = np.broadcast_shapes(*(v.shape for _, v in present))
        x = _term_matrix(present, shape)
        table = self.inertia[[t for t, _ in present]].reshape(len(present), -1)
        return (x @ table).reshape(shape + self.inertia.shape[1:])

    def fuel_loads(self, terms: dict[str, np.ndarray]) -> np.ndarray | None:
        """Inertial station loads per kilogram of each tank's fuel, (..., K, 3, n_stations), from the named inertial
        terms; None for a surface without tanks. A fuel state m (..., K) kg loads the stations by Σ_k m_k × this."""
        if self.fuel_inertia is None or not len(self.tank_names):
            return None
        present = [(t, np.asarray(terms[name], dtype=float)) for t, name in enumerate(INERTIA_TERMS) if name in terms]
        K = len(self.tank_names)
        if not present:
            return np.zeros((K,) + self.inertia.shape[1:])
        shape = np.broadcast_shapes(*(v.shape for _, v in present))
        x = _term_matrix(present, shape)
        table = self.fuel_inertia[:, [t for t, _ in present]]  # (K, T', 3, S)
        table = np.moveaxis(table, 1, 0).reshape(len(present), -1)
        return (x @ table).reshape(shape + (K,) + self.inertia.shape[1:])

    def fuel_term_tables(self, terms: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray] | None:
        """The inertial terms that load this surface's fuel, stacked (..., J), and their per-kilogram tables (K, J, 3,
        S): :meth:`fuel_loads` is Σ_j x_j × table_j, left uncontracted so that a caller combining fuel states contracts
        the small tables with the states first. None for a surface without tanks."""
        if self.fuel_inertia is None or not len(self.tank_names):
            return None
        present = [
            (t, np.asarray(terms[name], dtype=float))
            for t, name in enumerate(INERTIA_TERMS)
            if name in terms and np.any(self.fuel_inertia[:, t])
        ]
        if not present:
            return None
        shape = np.broadcast_shapes(*(v.shape for _, v in present))
        x = np.stack([np.broadcast_to(v, shape) for _, v in present], axis=-1)
        return x, self.fuel_inertia[:, [t for t, _ in present]]

    def strip_normal_force(self, qbar, mach, inputs) -> np.ndarray:
        """Aerodynamic normal force of each strip (..., n_strips), N."""
        return self._superpose(qbar, mach, inputs, self.strip_aero)


def _term_matrix(present, shape) -> np.ndarray:
    """The inertial terms ``present`` ((index, array) pairs) broadcast to ``shape``, one column each: (points, terms),
    each term written into its column at once."""
    x = np.empty((int(np.prod(shape, dtype=int)), len(present)))
    columns = x.reshape(tuple(shape) + (len(present),))
    for j, (_, v) in enumerate(present):
        columns[..., j] = v
    return x


@njit(cache=True)
def _superpose_kernel(qbar, index, weight, x, cols, table, out):
    """out[p] = q̄_p Σ_c x[c, p] ((1 − w_p) T[i_p, k_c] + w_p T[i_p + 1, k_c]) (zero inputs skipped)."""
    m, n_out = table.shape[0], table.shape[2]
    for p in range(out.shape[0]):
        i = index[p]
        j = min(i + 1, m - 1)
        w = weight[p]
        for col in range(n_out):
            out[p, col] = 0.0
        for c in range(cols.shape[0]):
            v = x[c, p] * qbar[p]
            if v == 0.0:
                continue
            a, b = v * (1.0 - w), v * w
            k = cols[c]
            for col in range(n_out):
                out[p, col] += a * table[i, k, col] + b * table[j, k, col]


def station_label(station) -> str:
    """Name of a load station: ``root``, ``side of body`` or ``"62.5% span"`` for a span fraction."""
    if station in ("root", "side_of_body", "side of body"):
        return str(station).replace("_", " ")
    f = float(station)
    if f == 0.0:
        return "root"
    return f"{f:.0%} span" if abs(f * 100 - round(f * 100)) < 1e-9 else f"{f:.1%} span"


def _strip_indices(lattice, surface: str) -> np.ndarray:
    for p in lattice.patches:
        if p.name == surface:
            return np.arange(p.strips.start, p.strips.stop)
    raise KeyError(f"no surface {surface!r} in the lattice")


def _station_matrices(s1, s2, x_axis_strip, x_axis_station, stations):
    """(3, n_stations, n_strips) matrices turning strip forces (with their X of application, see
    below) into shear, bending and torsion at each station: the outboard fraction of each strip
    (strips cut by a station contribute their outboard part, load uniform over the strip)."""
    lo, hi = np.minimum(s1, s2), np.maximum(s1, s2)
    width = np.maximum(hi - lo, 1e-12)
    frac = np.clip((hi[None, :] - stations[:, None]) / width[None, :], 0.0, 1.0)
    centre = np.maximum(lo[None, :], stations[:, None]) * 0.5 + hi[None, :] * 0.5
    arm = np.where(frac > 0, centre - stations[:, None], 0.0)
    return frac, frac * arm


def build_surface_loads(
    vl,
    surface: str,
    machs,
    masses,
    axis_fraction: float = 0.4,
    station_fractions=(0.0, 0.25, 0.5, 0.75),
    side_of_body: float | None = None,
    point_masses=(),
    solutions: dict | None = None,
    aircraft=None,
) -> SurfaceLoads:
    """Unit load tables of ``surface`` (lattice surface name; the right half for mirrored surfaces).

    ``masses``: total structural mass of the surface (both halves for a mirrored one), kg.
    ``point_masses``: (mass kg, X, Y, Z) items attached to the surface at their span station.
    ``side_of_body``: Y (m) of an extra station where the surface leaves the fuselage.
    ``solutions``: a store of the lattice's unit solutions (every surface's strips come from the same solve, and
    the lattice's geometry does not change with the masses), filled and reused by (Mach, input, value), and of each
    surface's aerodynamic tables (the geometry's alone: airplanes of one lattice, the sizing loop's passes, share them).
    ``aircraft``: for the wing, the file whose ``mass.fuel_tanks`` are spread on its strips (fuel tables per tank)."""
    store = {} if solutions is None else solutions  # without one, this build's own
    lat = vl.lattice
    idx = _strip_indices(lat, surface)
    vertical_surface = bool(np.all(np.abs(lat.ensy[idx]) > np.abs(lat.ensz[idx])))
    sign = np.sign(lat.ensy[idx]) if vertical_surface else np.sign(lat.ensz[idx])
    ny, nz = lat.ensy[idx] * sign, lat.ensz[idx] * sign  # normal up (or right for the fin)
    root = (
        lat.rle1[idx[0]]
        if abs(lat.rle1[idx[0], 1]) + abs(lat.rle1[idx[0], 2]) <= abs(lat.rle2[idx[0], 1]) + abs(lat.rle2[idx[0], 2])
        else lat.rle2[idx[0]]
    )

    def span_of(p):
        return np.hypot(p[..., 1] - root[1], p[..., 2] - root[2])

    s1, s2 = span_of(lat.rle1[idx]), span_of(lat.rle2[idx])
    s_mid = 0.5 * (s1 + s2)
    semispan = max(s1.max(), s2.max())
    chord = lat.chord[idx]
    x_axis = lat.rle[idx, 0] + axis_fraction * chord
    names = [station_label(f) for f in station_fractions]
    stations = [f * semispan for f in station_fractions]
    if side_of_body is not None and 0.0 < side_of_body < semispan:
        cos_dihedral = float(np.mean(np.abs(nz))) if not vertical_surface else 1.0
        stations.append(side_of_body / max(cos_dihedral, 1e-6))
        names.append("side of body")
    order = np.argsort(stations)
    stations = np.array(stations)[order]
    names = tuple(np.array(names, dtype=object)[order])
    x_axis_station = np.interp(stations, s_mid, x_axis)
    shear_m, bend_m = _station_matrices(s1, s2, x_axis, x_axis_station, stations)

    def integrate(force, x_load):
        """force (..., J), x_load (..., J) → (..., 3, S)."""
        shear = np.einsum("...j,sj->...s", force, shear_m)
        bend = np.einsum("...j,sj->...s", force, bend_m)
        tors = np.einsum("...j,sj->...s", force, shear_m) * x_axis_station - np.einsum(
            "...j,sj->...s", force * x_load, shear_m
        )
        return np.stack([shear, bend, tors], axis=-2)

    # --- unit aerodynamic solutions ---------------------------------------------------------
    controls = tuple(vl.control_names)
    inputs = ("one",) + RATE_INPUTS + controls
    xv = lat.rv[:, 0]

    def unit_tables():
        """The aerodynamic tables of every Mach number: station loads and strip forces per unit input, and the
        strips' vertical force (the geometry's alone: shared by the airplanes of one lattice)."""
        aero, strip_aero, vertical = [], [], []
        for m in machs:
            v = vl.at_mach(float(m))

            def solve(name, value):
                kw = {"alpha": 0.0, "beta": 0.0, "p_hat": 0.0, "q_hat": 0.0, "r_hat": 0.0}
                ctrl = {}
                if name in kw:
                    kw[name] = value
                elif name in controls:
                    ctrl[name] = value
                return v.strip_forces(**kw, controls=ctrl or None, rate_axes="body")  # noqa: B023  (called within this iteration)

            def state(name, value):
                key = (float(m), name, value)  # noqa: B023  (called within this iteration)
                if key not in store:
                    store[key] = solve(name, value)
                f_all, g = store[key]
                f = f_all[idx]
                normal = f[:, 1] * ny + f[:, 2] * nz
                gsum = np.add.reduceat(g, lat.first)[idx]
                gx = np.add.reduceat(g * xv, lat.first)[idx]
                return normal, gsum, gx

            base_n, base_g, base_gx = state("one", 0.0)
            # the strips' force per unit circulation, from the flow angle that loads this surface: α for a
            # horizontal surface, β for a fin (whose strips hardly respond to α)
            loading_angle = "beta" if np.mean(np.abs(ny)) > np.mean(np.abs(nz)) else "alpha"
            a_n, a_g, _ = state(loading_angle, EPS)
            am_n, am_g, _ = state(loading_angle, -EPS)
            # force per unit circulation of each strip (≈ 2 × strip width, the freestream Kutta–Joukowski force); where
            # the strip's circulation hardly moves with the loading angle the quotient is ill-conditioned (a swept
            # tail's root strip near M 0.94: 10⁴ × the Kutta–Joukowski value, or negative on its neighbours, which put
            # tens of MN·m of torsion at the root) and the Kutta–Joukowski value stands in for it
            d_g = a_g - am_g
            moves = np.abs(d_g) > 1e-14
            quotient = (a_n - am_n) / np.where(moves, d_g, 1.0)
            # the circulation's sign against the surface's normal is the lattice's (a fin's quotient is negative)
            kutta_joukowski = 2 * lat.width[idx] * (1.0 if np.median(quotient[moves]) >= 0 else -1.0)
            in_band = quotient / kutta_joukowski
            conditioned = moves & (in_band > RATIO_BAND[0]) & (in_band < RATIO_BAND[1])
            ratio = np.where(conditioned, quotient, kutta_joukowski)
            # each unit solution's moment about the strip's reference axis, Σ γ (X − X_axis) × the force per unit
            # circulation: taken about the axis, not the nose, so that the ratio (read from the loading angle's
            # solution) scales a lever of a few metres and not the strip's whole X (a 1 % mismatch between inputs
            # would otherwise move the load by 1 % of the distance from the nose)
            unit_n, unit_m = [base_n], [ratio * (base_gx - x_axis * base_g)]
            for name in inputs[1:]:
                pn, pg, pgx = state(name, EPS)
                mn, mg, mgx = state(name, -EPS)
                unit_n.append((pn - mn) / (2 * EPS))
                unit_m.append(ratio * ((pgx - mgx) - x_axis * (pg - mg)) / (2 * EPS))
            unit_n, unit_m = np.array(unit_n), np.array(unit_m)  # (K, J): force and its moment about the axis
            big = np.abs(unit_n) > 1e-12
            x_load = x_axis + np.where(big, unit_m / np.where(big, unit_n, 1.0), 0.0)
            aero.append(integrate(unit_n, x_load))
            strip_aero.append(unit_n)
            vertical.append(unit_n @ (np.zeros_like(nz) if vertical_surface else nz))
            del base_g
        return np.array(aero), np.array(strip_aero), np.array(vertical)

    tables_key = ("strip tables", surface, tuple(float(m) for m in machs), axis_fraction, tuple(stations), names)
    if tables_key not in store:
        store[tables_key] = unit_tables()
    aero, strip_aero, vertical = store[tables_key]

    # --- mass ------------------------------------------------------------------------------
    area = lat.chord[idx] * lat.width[idx]
    mirrored = any(p.name == surface + " (YDUP)" for p in lat.patches)
    half = 0.5 if mirrored else 1.0
    strip_mass = half * masses * area / area.sum()
    x_mass = x_axis.copy()
    z_mass = lat.rle[idx, 2].copy()
    y_mass = 0.5 * (lat.rle1[idx, 1] + lat.rle2[idx, 1])
    extra_force_mass = np.zeros_like(strip_mass)
    for p_mass, px, py, pz in point_masses:
        if mirrored and py < 0:
            continue
        for j, share in bracketing_shares(s_mid, float(np.hypot(py - root[1], pz - root[2]))):
            pm = p_mass * share
            total = strip_mass[j] + extra_force_mass[j] + pm
            x_mass[j] = (x_mass[j] * (strip_mass[j] + extra_force_mass[j]) + px * pm) / total
            z_mass[j] = (z_mass[j] * (strip_mass[j] + extra_force_mass[j]) + pz * pm) / total
            y_mass[j] = (y_mass[j] * (strip_mass[j] + extra_force_mass[j]) + py * pm) / total
            extra_force_mass[j] += pm
    mass = strip_mass + extra_force_mass

    def inertia_table(mass, x_mass, y_mass, z_mass):
        terms = np.array(
            [
                -mass * G0 * nz,
                -mass * nz,
                mass * nz * x_mass,
                -mass * G0 * ny,
                -mass * ny,
                mass * ny * x_mass,
                mass * ny,
                -mass * ny * z_mass + mass * nz * y_mass,
            ]
        )
        return integrate(terms, np.broadcast_to(x_mass, terms.shape))

    inertia = inertia_table(mass, x_mass, y_mass, z_mass)
    notes = []
    tank_names, fuel_inertia, shares = (), None, None
    if aircraft is not None and aircraft.mass.fuel_tanks and not vertical_surface:
        y_strip = 0.5 * (lat.rle1[idx, 1] + lat.rle2[idx, 1])
        tank_names, shares, tank_notes = wing_tank_shares(
            aircraft, np.abs(lat.rle1[idx, 1]), np.abs(lat.rle2[idx, 1]), chord, side_of_body or 0.0
        )
        notes += tank_notes
        z_strip = lat.rle[idx, 2]
        fuel_inertia = np.array([inertia_table(share, x_axis, y_strip, z_strip) for share in shares])
    if masses <= 0:
        notes.append(f"{surface}: no structural mass declared; inertial loads are zero")
    return SurfaceLoads(
        surface,
        inputs,
        np.asarray(machs, dtype=float),
        names,
        stations,
        np.interp(stations, s_mid, (lat.rle[idx, 2] if vertical_surface else lat.rle[idx, 1])),
        s_mid,
        x_axis,
        mass,
        aero,
        inertia,
        strip_aero,
        axis_fraction,
        notes,
        tank_names,
        fuel_inertia,
        shares,
        vertical,
        float(np.sum(chord**2 * lat.width[idx]) / np.sum(chord * lat.width[idx])),
    )


def surface_mass(aircraft, surface: str) -> float:
    """Structural mass (kg) of the surface from the aircraft file's components (0 if not declared)."""
    keys = SURFACE_COMPONENTS.get(surface, (surface,))
    total = 0.0
    for c in aircraft.mass.components:
        if c.name.strip().lower() in keys:
            total += c.mass
    return total


def bracketing_shares(s_mid: np.ndarray, span: float) -> list[tuple[int, float]]:
    """A point mass at ``span`` shared between the two strips whose middles bracket it, in inverse proportion to the
    distance (all on the end strip beyond the outermost middles): its first moment about every station inboard of
    both strips is the point's own (on the nearest strip alone, an engine 0.8 m from a strip's middle lost 8 % of its
    relief of the side-of-body bending)."""
    order = np.argsort(s_mid)
    s = s_mid[order]
    if span <= s[0]:
        return [(int(order[0]), 1.0)]
    if span >= s[-1]:
        return [(int(order[-1]), 1.0)]
    k = int(np.searchsorted(s, span))
    w = float((span - s[k - 1]) / (s[k] - s[k - 1]))
    return [(int(order[k - 1]), 1.0 - w), (int(order[k]), w)]


def wing_point_masses(aircraft) -> list[tuple[float, float, float, float]]:
    """Propulsion components off the plane of symmetry (engines, nacelles) as wing point masses."""
    return [
        (c.mass, c.cg.x, c.cg.y, c.cg.z)
        for c in aircraft.mass.components
        if c.group == "propulsion" and abs(c.cg.y) > 0.0
    ]


@dataclass
class AirplaneLoads:
    """The loads models of the lifting surfaces of one aircraft (wing and tail halves, fin)."""

    surfaces: dict[str, SurfaceLoads]
    notes: list[str]

    def __getitem__(self, name: str) -> SurfaceLoads:
        return self.surfaces[name]


DEFAULT_STATIONS = (0.0, 0.25, 0.5, 0.75)


def declared_station_fractions(aircraft, surface: str) -> tuple[float, ...]:
    """The default station fractions plus those of the declared capabilities (``structure`` section)."""
    st = getattr(aircraft, "structure", None)
    extra = [
        float(c.station)
        for c in (getattr(st, surface) if st is not None else ())
        if not isinstance(c.station, str) and float(c.station) < 1.0
    ]
    return tuple(sorted(set(DEFAULT_STATIONS) | set(extra)))


def build_airplane_loads(
    aircraft, vl, machs, axis_fraction: float = 0.4, solutions: dict | None = None
) -> AirplaneLoads:
    """Wing, horizontal tail and fin loads models from the lattice ``vl`` at the Mach breakpoints
    (stations: :data:`DEFAULT_STATIONS` and those of the declared capabilities); the three surfaces share the
    lattice's unit solutions (``solutions``: a store kept with the lattice, see :func:`build_surface_loads`)."""
    solutions = {} if solutions is None else solutions
    g = aircraft.geometry
    sob = 0.5 * g.fuselage.width if g is not None and g.fuselage is not None else None
    out = {}
    notes = [
        "strip loads from unit vortex-lattice solutions (linear superposition, quasi-steady)",
        f"torsion about the {axis_fraction:.0%} chord line; strip masses at that line",
        "wing fuel: one inertial table per declared tank (volume-weighted over its bay); the loads rules add the "
        "fuel state they evaluate",
    ]
    for name in ("wing", "horizontal_tail", "vertical_tail"):
        pm = wing_point_masses(aircraft) if name == "wing" else ()
        out[name] = build_surface_loads(
            vl,
            name,
            machs,
            surface_mass(aircraft, name),
            axis_fraction,
            station_fractions=declared_station_fractions(aircraft, name),
            side_of_body=None if name == "vertical_tail" else sob,
            point_masses=pm,
            solutions=solutions,
            aircraft=aircraft if name == "wing" else None,
        )
        notes += out[name].notes
    return AirplaneLoads(out, notes)


def airplane_loads(ctx, configuration: str = "clean") -> AirplaneLoads:
    """The memoised loads model of ``configuration`` (needs the vortex lattice: geometry declared), on the lattice of
    :func:`certkit.models.aero.airplane.lattice_derivatives` (its ``flap`` control spreads a configuration's
    flap lift)."""

    def build():
        aero = ctx.aero(configuration)
        if aero.lattice is None:
            raise ValueError(
                f"configuration {configuration!r} uses declared derivative tables: the strip loads "
                "model needs the geometry's vortex lattice"
            )
        # the flight model's lattice (the wing's flap one of its controls) and its unit solutions: kept under "aero"
        # keys, a Context that shares the aerodynamics (the sizing loop's next airplane, same geometry) shares them too
        solutions = ctx.memo(("aero", "loads unit solutions", configuration, id(aero.lattice)), dict)
        return build_airplane_loads(ctx.aircraft, aero.lattice, aero.mach, solutions=solutions)

    return ctx.memo(("airplane_loads", configuration), build)
