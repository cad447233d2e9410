"""Paneling: surfaces → strips → horseshoe vortices, normals and control-rotation normals.

Follows the discretisation of AVL (Drela & Youngren, AVL 3.x, routines MAKESURF, SDUPL, ENCALC as
described in the user primer): each strip carries ``n_chord`` horseshoe vortices whose bound legs lie
at the quarter point of each chordwise element and whose control points lie at its three-quarter
point; strip edges interpolate the defining sections linearly, incidence through the chord
projections, camber slope and control hinge lines chord-weighted between the two sections. Control
deflections enter linearly through a rotation of the control-point normal about the hinge axis.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .geometry import (
    CamberLine,
    Configuration,
    GeometryError,
    Surface,
    chord_fractions,
    spacing_parameter,
    span_fractions,
)


@dataclass(frozen=True)
class SurfacePatch:
    """Where one (possibly mirrored) surface sits in the lattice arrays."""

    name: str
    strips: slice
    vortices: slice
    n_chord: int
    load: bool
    mirrored: bool


@dataclass
class Lattice:
    """Arrays of a paneled configuration (geometry frame, metres).

    Per vortex (N): ``rv1``, ``rv2`` bound-leg ends, ``rv`` bound-leg midpoint, ``rc`` control point,
    ``normal`` control-point normal, ``normal_control`` (n_controls, N, 3) normal change per radian of
    each control variable, ``strip`` index, ``chord`` of its strip, ``dx`` element chord length.
    Per strip (J): leading edges ``rle1``/``rle2``/``rle`` and chords ``chord1``/``chord2``/``chord``
    at edge 1, edge 2 and centre, ``width``, in-plane normal ``ensy``/``ensz``, ``first``/``count``
    vortex indices, ``component``, ``wake``, ``alpha_beta``, ``load`` flags. If the configuration
    is mirror-symmetric about y = 0, ``mirror[i]`` is the image of vortex i and ``mirror_sign[i]``
    is +1 (image with reversed bound leg, as built by YDUPLICATE) or −1 (vortex in the plane of
    symmetry, its own image with reversed sense); otherwise both are None."""

    rv1: np.ndarray
    rv2: np.ndarray
    rv: np.ndarray
    rc: np.ndarray
    normal: np.ndarray
    normal_control: np.ndarray
    vortex_strip: np.ndarray
    dx: np.ndarray
    rle1: np.ndarray
    rle2: np.ndarray
    rle: np.ndarray
    chord1: np.ndarray
    chord2: np.ndarray
    chord: np.ndarray
    width: np.ndarray
    ensy: np.ndarray
    ensz: np.ndarray
    first: np.ndarray
    count: np.ndarray
    component: np.ndarray
    wake: np.ndarray
    alpha_beta: np.ndarray
    load: np.ndarray
    patches: list[SurfacePatch]
    control_names: tuple[str, ...]
    mirror: np.ndarray | None = None
    mirror_sign: np.ndarray | None = None
    control_fraction: np.ndarray | None = None  # (n_controls, N): gain × fraction of each element on the control
    hinge_axis: np.ndarray | None = None  # (n_controls, J, 3): unit hinge vector of each strip (zero: no control)
    hinge_point: np.ndarray | None = None  # (n_controls, J, 3): hinge-line point at each strip's centre (AVL PHINGE)

    @property
    def n_vortices(self) -> int:
        return self.rv.shape[0]

    @property
    def n_strips(self) -> int:
        return self.chord.shape[0]


def _spanwise_nodes(surface: Surface, yzlen: np.ndarray) -> tuple[np.ndarray, np.ndarray, list[int]]:
    """Strip-edge arc positions, control-point arc positions and the node index of each section."""
    where = f"surface {surface.name!r}"
    nsec = len(yzlen)
    if surface.n_span:
        nvs = int(surface.n_span)
        f = span_fractions(2 * nvs + 1, spacing_parameter(surface.span_spacing))
        ypt = yzlen[0] + (yzlen[-1] - yzlen[0]) * f[0::2]
        ycp = yzlen[0] + (yzlen[-1] - yzlen[0]) * f[1::2]
        iptloc = [0] + [int(np.argmin(np.abs(yzlen[k] - ypt))) for k in range(1, nsec - 1)] + [nvs]
        # a section closer to its neighbour than one strip takes the next free node (a narrow strip between them)
        # instead of sharing its node; an order-preserving shift, the same nodes as before whenever they differ
        for k in range(1, nsec - 1):
            iptloc[k] = max(iptloc[k], iptloc[k - 1] + 1)
        for k in range(nsec - 2, 0, -1):
            iptloc[k] = min(iptloc[k], iptloc[k + 1] - 1)
        # move the nodes nearest each interior section onto it, rescaling the intervals on both sides
        for k in range(1, nsec - 1):
            for lo, hi, anchor_lo in ((iptloc[k - 1], iptloc[k], True), (iptloc[k], iptloc[k + 1], False)):
                if lo == hi:
                    raise GeometryError(
                        f"{where}, section {k + 1}: too few spanwise vortices (n_span={nvs}) to put a strip edge on "
                        "every section"
                    )
                y1 = ypt[lo]
                if anchor_lo:
                    start, scale = yzlen[k - 1], (yzlen[k] - yzlen[k - 1]) / (ypt[hi] - y1)
                else:
                    start, scale = yzlen[k], (ypt[hi] - yzlen[k]) / (ypt[hi] - y1)
                ypt[lo:hi] = start + scale * (ypt[lo:hi] - y1)
                ycp[lo:hi] = start + scale * (ycp[lo:hi] - y1)
        return ypt, ycp, iptloc
    ypt_list, ycp_list, iptloc = [yzlen[0]], [], [0]
    for k in range(nsec - 1):
        sec = surface.sections[k]
        if sec.n_span < 1:
            raise GeometryError(
                f"{where}, section {k + 1}: no spanwise vortices (give the surface or this section an n_span)"
            )
        f = span_fractions(2 * sec.n_span + 1, spacing_parameter(sec.span_spacing))
        start, d = ypt_list[-1], yzlen[k + 1] - yzlen[k]
        ycp_list.extend(start + d * f[1::2])
        ypt_list.extend(start + d * f[2::2])
        iptloc.append(len(ypt_list) - 1)
    return np.array(ypt_list), np.array(ycp_list), iptloc


def _check_sections(surface: Surface, le: np.ndarray, chords: np.ndarray) -> None:
    where = f"surface {surface.name!r}"
    if len(surface.sections) < 2:
        raise GeometryError(f"{where}: needs at least two sections, has {len(surface.sections)}")
    if surface.n_chord < 1:
        raise GeometryError(f"{where}: n_chord must be at least 1")
    for k, c in enumerate(chords):
        if not (c > 0.0 and np.isfinite(c)):
            raise GeometryError(f"{where}, section {k + 1}: chord {c} must be positive (zero-area panels)")
    if not np.all(np.isfinite(le)):
        raise GeometryError(f"{where}: non-finite section coordinates")
    seg = np.diff(le[:, 1:], axis=0)
    length = np.hypot(seg[:, 0], seg[:, 1])
    for k, ln in enumerate(length):
        if ln <= 1e-9 * max(1.0, float(np.max(chords))):
            raise GeometryError(
                f"{where}, sections {k + 1} and {k + 2}: no span between them in the y-z plane (zero span)"
            )
    for k in range(len(seg) - 1):
        if float(seg[k] @ seg[k + 1]) < 0.0:
            raise GeometryError(f"{where}, section {k + 2}: the surface folds back on itself here (sections cross)")
    for k, sec in enumerate(surface.sections):
        names = [c.name for c in sec.controls]
        for c in sec.controls:
            if not (0.0 <= abs(c.hinge_x_over_c) <= 1.0):
                raise GeometryError(
                    f"{where}, section {k + 1}: control {c.name!r} hinge x/c {c.hinge_x_over_c} outside the chord"
                )
            neighbours = [surface.sections[j] for j in (k - 1, k + 1) if 0 <= j < len(surface.sections)]
            if not any(c.name in [d.name for d in nb.controls] for nb in neighbours):
                raise GeometryError(
                    f"{where}, section {k + 1}: control {c.name!r} is on no neighbouring section, so it lies outside "
                    "the surface (a control acts between two sections carrying it)"
                )
        if len(set(names)) != len(names):
            raise GeometryError(f"{where}, section {k + 1}: a control is declared twice")


def _panel_surface(surface: Surface, control_index: dict[str, int]) -> dict[str, np.ndarray]:
    """Strips and vortices of one surface (not its mirror image)."""
    where = f"surface {surface.name!r}"
    scale = np.asarray(surface.scale, float)
    shift = np.asarray(surface.translate, float)
    le_raw = np.array([s.leading_edge for s in surface.sections], float)
    le = le_raw * scale + shift
    chords = np.array([s.chord for s in surface.sections], float) * scale[0]
    _check_sections(surface, le, chords)
    inc = np.array([s.incidence for s in surface.sections], float) + surface.incidence
    seg_raw = np.diff(le_raw[:, 1:], axis=0)
    yzlen = np.concatenate([[0.0], np.cumsum(np.hypot(seg_raw[:, 0], seg_raw[:, 1]))])  # AVL: unscaled
    ypt, ycp, iptloc = _spanwise_nodes(surface, yzlen)
    nc = int(surface.n_chord)
    cspace = spacing_parameter(surface.chord_spacing)
    n_ctrl = len(control_index)
    cambers = [s.camber or CamberLine.flat() for s in surface.sections]
    claf = np.array([s.claf for s in surface.sections], float)

    out: dict[str, list] = {
        k: []
        for k in (
            "rle1",
            "rle2",
            "rle",
            "chord1",
            "chord2",
            "chord",
            "width",
            "ainc",
            "xpt",
            "xvr",
            "xcp",
            "slope",
            "dcontrol",
            "hinge",
            "dupsign",
            "hinge_point",
        )
    }
    for k in range(len(surface.sections) - 1):
        lo, hi = iptloc[k], iptloc[k + 1]
        span_lo, span_hi = ypt[lo], ypt[hi]
        f1 = (ypt[lo:hi] - span_lo) / (span_hi - span_lo)
        f2 = (ypt[lo + 1 : hi + 1] - span_lo) / (span_hi - span_lo)
        fc = (ycp[lo:hi] - span_lo) / (span_hi - span_lo)
        le_l, le_r = le[k], le[k + 1]
        c_l, c_r = chords[k], chords[k + 1]
        width = float(np.hypot(*(le_r[1:] - le_l[1:])))
        lerp = lambda f, a, b: (1.0 - f)[:, None] * a + f[:, None] * b  # noqa: E731
        chord_c = (1.0 - fc) * c_l + fc * c_r
        w = np.abs(f2 - f1) * width
        if np.any(w <= 1e-12 * width):
            raise GeometryError(f"{where}, sections {k + 1}-{k + 2}: zero-width strip (zero-area panels)")
        out["rle1"].append(lerp(f1, le_l, le_r))
        out["rle2"].append(lerp(f2, le_l, le_r))
        out["rle"].append(lerp(fc, le_l, le_r))
        out["chord1"].append((1.0 - f1) * c_l + f1 * c_r)
        out["chord2"].append((1.0 - f2) * c_l + f2 * c_r)
        out["chord"].append(chord_c)
        out["width"].append(w)
        chsin = c_l * np.sin(inc[k]) + fc * (c_r * np.sin(inc[k + 1]) - c_l * np.sin(inc[k]))
        chcos = c_l * np.cos(inc[k]) + fc * (c_r * np.cos(inc[k + 1]) - c_l * np.cos(inc[k]))
        out["ainc"].append(np.arctan2(chsin, chcos))
        wl, wr = (1.0 - fc) * c_l / chord_c, fc * c_r / chord_c  # chord-weighted interpolation
        claf_c = wl * claf[k] + wr * claf[k + 1]
        xpt = np.empty((hi - lo, nc + 1))
        xvr = np.empty((hi - lo, nc))
        xcp = np.empty((hi - lo, nc))
        for value in set(claf_c.tolist()):  # not np.unique: it imports numpy.ma (10 ms of `certkit derivatives`)
            m = claf_c == value
            e, v, c = chord_fractions(nc, cspace, float(value))
            xpt[m], xvr[m], xcp[m] = e, v, c
        out["xpt"].append(xpt)
        out["xvr"].append(xvr)
        out["xcp"].append(xcp)
        out["slope"].append(wl[:, None] * cambers[k].slope(xcp) + wr[:, None] * cambers[k + 1].slope(xcp))

        dcontrol = np.zeros((n_ctrl, hi - lo, nc))
        hinge = np.zeros((n_ctrl, hi - lo, 3))
        hinge_point = np.zeros((n_ctrl, hi - lo, 3))
        dups = np.ones((n_ctrl, hi - lo))
        left = {c.name: c for c in surface.sections[k].controls}
        right = {c.name: c for c in surface.sections[k + 1].controls}
        for name in left.keys() & right.keys():
            n = control_index[name]
            cl_, cr_ = left[name], right[name]
            gain = cl_.gain * (1.0 - fc) + cr_.gain * fc
            xhd = c_l * cl_.hinge_x_over_c * (1.0 - fc) + c_r * cr_.hinge_x_over_c * fc
            x_lead = np.where(xhd >= 0.0, xhd, 0.0)
            x_trail = np.where(xhd >= 0.0, chord_c, -xhd)
            dxoc = np.diff(xpt, axis=1)
            frac_le = np.clip((x_lead / chord_c)[:, None] - xpt[:, :-1], 0.0, dxoc) / dxoc
            frac_te = np.clip((x_trail / chord_c)[:, None] - xpt[:, :-1], 0.0, dxoc) / dxoc
            dcontrol[n] = gain[:, None] * (frac_te - frac_le)
            hinge_point[n] = lerp(fc, le_l, le_r) + np.abs(xhd)[:, None] * np.array([1.0, 0.0, 0.0])
            vh = np.asarray(cl_.hinge_vector, float) * scale
            if not np.any(vh):
                raw_l, raw_r = le_raw[k], le_raw[k + 1]
                vh = (
                    np.array(
                        [
                            raw_r[0]
                            + abs(surface.sections[k + 1].chord * cr_.hinge_x_over_c)
                            - raw_l[0]
                            - abs(surface.sections[k].chord * cl_.hinge_x_over_c),
                            raw_r[1] - raw_l[1],
                            raw_r[2] - raw_l[2],
                        ]
                    )
                    * scale
                )
            hinge[n] = vh / np.linalg.norm(vh)
            dups[n] = cl_.duplicate_sign
        out["dcontrol"].append(dcontrol)
        out["hinge"].append(hinge)
        out["dupsign"].append(dups)
        out["hinge_point"].append(hinge_point)

    strips = {
        k: np.concatenate(v, axis=(1 if k in ("dcontrol", "hinge", "dupsign", "hinge_point") else 0))
        for k, v in out.items()
    }
    x_ = np.array([1.0, 0.0, 0.0])
    strips["rv1"] = strips["rle1"][:, None, :] + (strips["xvr"] * strips["chord1"][:, None])[..., None] * x_
    strips["rv2"] = strips["rle2"][:, None, :] + (strips["xvr"] * strips["chord2"][:, None])[..., None] * x_
    strips["rv"] = strips["rle"][:, None, :] + (strips["xvr"] * strips["chord"][:, None])[..., None] * x_
    strips["rc"] = strips["rle"][:, None, :] + (strips["xcp"] * strips["chord"][:, None])[..., None] * x_
    strips["dx"] = np.diff(strips["xpt"], axis=1) * strips["chord"][:, None]
    return strips


def _mirror(strips: dict[str, np.ndarray], y_mirror: float) -> dict[str, np.ndarray]:
    """Image surface about y = y_mirror; edges 1 and 2 swap so positive circulation keeps its sense;
    hinge vectors mirror, deflections change sign times the control's duplicate sign (AVL SDUPL)."""
    flip = lambda r: r * np.array([1.0, -1.0, 1.0]) + np.array([0.0, 2.0 * y_mirror, 0.0])  # noqa: E731
    m = dict(strips)
    m["rle1"], m["rle2"], m["rle"] = flip(strips["rle2"]), flip(strips["rle1"]), flip(strips["rle"])
    m["chord1"], m["chord2"] = strips["chord2"], strips["chord1"]
    m["rv1"], m["rv2"] = flip(strips["rv2"]), flip(strips["rv1"])
    m["rv"], m["rc"] = flip(strips["rv"]), flip(strips["rc"])
    m["hinge"] = strips["hinge"] * np.array([1.0, -1.0, 1.0])
    m["dcontrol"] = -strips["dcontrol"] * strips["dupsign"][..., None]
    m["hinge_point"] = flip(strips["hinge_point"])
    return m


def _normals(rv1, rv2, slope, ainc, dcontrol, hinge):
    """Control-point normals (AVL ENCALC): the chord line tilted by incidence minus camber slope in
    the strip's plane, crossed with the bound leg; and their change per radian of each control
    (rotation about the hinge axis, linearised at zero deflection)."""
    d_first = rv2[:, 0] - rv1[:, 0]
    d_last = rv2[:, -1] - rv1[:, -1]
    dt = 0.75 * d_first + 0.25 * d_last
    yz = np.hypot(dt[:, 1], dt[:, 2])
    ensy, ensz = -dt[:, 2] / yz, dt[:, 1] / yz
    ang = ainc[:, None] - np.arctan(slope)
    s, c = np.sin(ang), np.cos(ang)
    ec = np.stack([c, -s * ensy[:, None], -s * ensz[:, None]], axis=-1)
    eb = rv2 - rv1
    eb = eb / np.linalg.norm(eb, axis=-1, keepdims=True)
    n = np.cross(ec, eb)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    h = hinge[:, :, None, :]  # (ctrl, strip, 1, 3)
    ep = n[None] - np.sum(n[None] * h, axis=-1, keepdims=True) * h
    nd = dcontrol[..., None] * np.cross(np.broadcast_to(h, ep.shape), ep)
    return n, nd, ensy, ensz


def build_lattice(config: Configuration) -> Lattice:
    """Panel every surface of ``config`` (and its mirror image) into one :class:`Lattice`."""
    names = config.control_names
    control_index = {n: i for i, n in enumerate(names)}
    blocks, patches = [], []
    next_component = 1 + max([s.component for s in config.surfaces if s.component is not None] or [0])
    n_strips = n_vort = 0
    for surface in config.surfaces:
        strips = _panel_surface(surface, control_index)
        if surface.component is None:
            comp = next_component
            next_component += 1
        else:
            comp = surface.component
        images = [(strips, False)]
        if surface.y_duplicate is not None:
            images.append((_mirror(strips, surface.y_duplicate), True))
        for data, mirrored in images:
            js, nc = data["chord"].shape[0], data["xvr"].shape[1]
            n, nd, ensy, ensz = _normals(
                data["rv1"], data["rv2"], data["slope"], data["ainc"], data["dcontrol"], data["hinge"]
            )
            blocks.append(
                dict(
                    data,
                    normal=n,
                    normal_control=nd,
                    ensy=ensy,
                    ensz=ensz,
                    component=np.full(js, comp),
                    wake=np.full(js, surface.wake),
                    alpha_beta=np.full(js, surface.alpha_beta),
                    load=np.full(js, surface.load),
                    count=np.full(js, nc),
                )
            )
            label = surface.name + (" (YDUP)" if mirrored else "")
            patches.append(
                SurfacePatch(
                    label, slice(n_strips, n_strips + js), slice(n_vort, n_vort + js * nc), nc, surface.load, mirrored
                )
            )
            n_strips += js
            n_vort += js * nc

    def cat_strip(key):
        return np.concatenate([b[key] for b in blocks])

    def cat_vort(key):
        return np.concatenate([b[key].reshape(-1, *b[key].shape[2:]) for b in blocks])

    count = cat_strip("count")
    mirror, mirror_sign = _mirror_map(config, patches, blocks)
    first = np.concatenate([[0], np.cumsum(count)[:-1]])
    nd = np.concatenate(
        [b["normal_control"].reshape(len(names), b["normal"].shape[0] * b["normal"].shape[1], 3) for b in blocks],
        axis=1,
    )
    return Lattice(
        rv1=cat_vort("rv1"),
        rv2=cat_vort("rv2"),
        rv=cat_vort("rv"),
        rc=cat_vort("rc"),
        normal=cat_vort("normal"),
        normal_control=nd,
        vortex_strip=np.repeat(np.arange(len(count)), count),
        dx=cat_vort("dx"),
        rle1=cat_strip("rle1"),
        rle2=cat_strip("rle2"),
        rle=cat_strip("rle"),
        chord1=cat_strip("chord1"),
        chord2=cat_strip("chord2"),
        chord=cat_strip("chord"),
        width=cat_strip("width"),
        ensy=cat_strip("ensy"),
        ensz=cat_strip("ensz"),
        first=first,
        count=count,
        component=cat_strip("component"),
        wake=cat_strip("wake"),
        alpha_beta=cat_strip("alpha_beta"),
        load=cat_strip("load"),
        patches=patches,
        control_names=names,
        mirror=mirror,
        mirror_sign=mirror_sign,
        control_fraction=np.concatenate(
            [b["dcontrol"].reshape(len(names), b["xvr"].shape[0] * b["xvr"].shape[1]) for b in blocks], axis=1
        ),
        hinge_axis=np.concatenate([b["hinge"] for b in blocks], axis=1),
        hinge_point=np.concatenate([b["hinge_point"] for b in blocks], axis=1),
    )


def _mirror_map(config: Configuration, patches: list[SurfacePatch], blocks: list[dict]):
    """Vortex ↔ image map when every surface is either mirrored about y = 0 or lies in y = 0."""
    n = sum(b["rv"].shape[0] * b["rv"].shape[1] for b in blocks)
    mirror = np.arange(n)
    sign = np.ones(n)
    k = 0
    for surface in config.surfaces:
        patch = patches[k]
        if surface.y_duplicate is not None:
            if surface.y_duplicate != 0.0:
                return None, None
            image = patches[k + 1]
            mirror[patch.vortices] = np.arange(image.vortices.start, image.vortices.stop)
            mirror[image.vortices] = np.arange(patch.vortices.start, patch.vortices.stop)
            k += 2
        else:
            b = blocks[k]
            if not (
                np.all(b["rv1"][..., 1] == 0.0) and np.all(b["rv2"][..., 1] == 0.0) and np.all(b["rc"][..., 1] == 0.0)
            ):
                return None, None
            sign[patch.vortices] = -1.0
            k += 1
    return mirror, sign
