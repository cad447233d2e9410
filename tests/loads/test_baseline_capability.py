"""The baseline's declared structural capability (aircraft/lta.yaml ``structure:``) recomputed from its
documented derivation (docs/baseline-sources.md §10): an idealised two-spar box at each station, its cover
and spar-web material sized from the surface's structural mass by a mass-budget, fully-stressed
distribution, and handbook material allowables.

Method (docs/baseline-sources.md §10 has the sources and the reasoning):

* planform: trapezoid from area, aspect ratio and taper of the aircraft file; chord c(η) = c_r (1 − (1 − λ) η).
* box: front and rear spar at fixed chord fractions; spar heights and the mean box depth from the NACA
  4-digit thickness distribution at the declared thickness ratio; bending lever = mean depth − cover
  thickness (centroid to centroid, Megson §16 idealisation: the covers carry the bending, the webs the shear).
* material budget: covers (skin + stringers, smeared) carry f_cov and spar webs f_web of the surface's
  structural mass; their spanwise distribution is fully stressed for a Schrenk span load (cover area ∝
  M(η)/h(η), web thickness ∝ V(η)/(h_fs + h_rs)) above a minimum gauge; the constant is set so the mass matches.
* allowables: bending M = σ A_cover h, shear V = τ t_web (h_fs + h_rs), torsion T = 2 A_box min(τ t) over the
  walls (Bredt–Batho). Aluminium (wing): limit from yield (Fty, Fcy, 0.577 Fty in shear), ultimate from
  Ftu, Fcy, Fsu; the sense decides which cover is in compression. CFRP (tails, 777 empennage): laminate
  moduli by classical lamination theory, design ultimate strains; limit = ultimate (linear to failure).

Run ``python -m tests.loads.test_baseline_capability`` to print the table of docs/baseline-sources.md §10.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pytest

from certkit.models.structure.section import laminate_moduli as _laminate_moduli
from certkit.models.structure.section import naca_thickness
from certkit.units import FT, LB

MPA = 1e6

# --------------------------------------------------------------------------- documented inputs (§10)

#: aluminium alloys of the 777 wing box (Starke & Staley 1996): MMPDS-typical design values, MPa
AL = {
    "7055-T7751 (upper cover)": dict(Ftu=621.0, Fty=600.0, Fcy=600.0, Fsu=359.0),
    "2324-T39 (lower cover)": dict(Ftu=476.0, Fty=393.0, Fcy=372.0, Fsu=276.0),
    "7050-T7451 (spar webs)": dict(Ftu=496.0, Fty=434.0, Fcy=427.0, Fsu=283.0),
}
AL_E = 71.0e3  # MPa, compression modulus of the 7xxx/2xxx alloys
AL_DENSITY = 2800.0  # kg/m³
SHEAR_YIELD = 0.577  # von Mises: shear yield = 0.577 Fty

#: representative intermediate-modulus carbon / toughened epoxy ply (T800H/3900-2 class, 60 % Vf)
PLY = dict(E1=155.0e3, E2=8.8e3, G12=4.8e3, nu12=0.32)  # MPa
CFRP_DENSITY = 1580.0  # kg/m³
COVER_LAYUP = {0: 0.40, 45: 0.25, -45: 0.25, 90: 0.10}  # skins and stringers, fraction of plies
WEB_LAYUP = {0: 0.10, 45: 0.40, -45: 0.40, 90: 0.10}  # spar webs
STRAIN_ULTIMATE = dict(compression=0.0040, tension=0.0045, shear=0.0080)  # design ultimate strains (BVID, hot/wet)

#: structural fractions and idealisation constants
COVER_FRACTION = 0.42  # covers (skin + stringers) / surface structural mass
WEB_FRACTION = 0.07  # spar webs / surface structural mass
SKIN_FRACTION = 0.60  # skin / (skin + stringers) of a cover
RIB_PITCH = 0.65  # m, for the Farrar panel check
FARRAR_F = 0.81  # Farrar efficiency of a Z-stringer panel
MIN_COVER = {"aluminium": 3.0e-3, "cfrp": 2.5e-3}  # m, minimum smeared cover thickness
MIN_WEB = {"aluminium": 2.5e-3, "cfrp": 2.0e-3}  # m


@dataclass(frozen=True)
class Surface:
    name: str
    area_ft2: float
    aspect_ratio: float
    taper: float
    thickness_ratio: float
    structural_mass_lb: float
    halves: int  # 2 for the wing and tailplane (both halves in the mass), 1 for the fin
    front_spar: float
    rear_spar: float
    material: str  # aluminium or cfrp
    stations: tuple[tuple[str, float], ...]  # (name, η)

    @property
    def span(self) -> float:  # m, full span (fin: height)
        return math.sqrt(self.aspect_ratio * self.area_ft2) * FT

    @property
    def semispan(self) -> float:
        return self.span / self.halves

    @property
    def root_chord(self) -> float:
        return 2.0 * self.area_ft2 * FT**2 / (self.halves * self.semispan * (1.0 + self.taper))


FUSELAGE_HALF_WIDTH_FT = 20.76 / 2
SURFACES = (
    Surface(
        "wing",
        4927.3,
        8.81,
        0.18,
        0.11,
        72000.0,
        2,
        0.15,
        0.60,
        "aluminium",
        (("root", 0.0), ("side_of_body", FUSELAGE_HALF_WIDTH_FT / (math.sqrt(8.81 * 4927.3) / 2))),
    ),
    Surface(
        "horizontal_tail",
        1119.2,
        4.62,
        0.33,
        0.088,
        5800.0,
        2,
        0.15,
        0.65,
        "cfrp",
        (("root", 0.0), ("side_of_body", FUSELAGE_HALF_WIDTH_FT / (math.sqrt(4.62 * 1119.2) / 2))),
    ),
    Surface("vertical_tail", 527.84, 1.84, 0.30, 0.10, 3800.0, 1, 0.15, 0.65, "cfrp", (("root", 0.0), ("0.5", 0.5))),
)

# --------------------------------------------------------------------------- the arithmetic


def laminate_moduli(layup) -> tuple[float, float]:
    """In-plane E_x and G_xy (MPa) of a balanced symmetric laminate of the §10 ply (classical lamination theory)."""
    return _laminate_moduli(PLY, layup)


def schrenk_shear_moment(eta, taper):
    """Shear and bending shapes (per unit total half-span load, span fraction units) of the Schrenk
    span load l(η) = ½ [c(η)/c̄ + (4/π)√(1 − η²)], integrated from the tip."""
    c_over_mean = (1.0 - (1.0 - taper) * eta) / ((1.0 + taper) / 2.0)
    load = 0.5 * (c_over_mean + 4.0 / math.pi * np.sqrt(np.clip(1.0 - eta**2, 0.0, None)))
    d = np.diff(eta)
    seg = 0.5 * (load[1:] + load[:-1]) * d
    shear = np.concatenate([np.cumsum(seg[::-1])[::-1], [0.0]])
    mseg = 0.5 * (shear[1:] + shear[:-1]) * d
    moment = np.concatenate([np.cumsum(mseg[::-1])[::-1], [0.0]])
    return shear, moment


def _budget(shape, floor, length, mass):
    """Constant K such that length × ∫ max(K·shape, floor) dη = mass / density (bisection); returns
    the distribution max(K·shape, floor)."""
    eta = np.linspace(0.0, 1.0, shape.size)

    def volume(k):
        return length * np.trapezoid(np.maximum(k * shape, floor), eta)

    lo, hi = 0.0, 1.0
    while volume(hi) < mass:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if volume(mid) < mass else (lo, mid)
    return np.maximum(0.5 * (lo + hi) * shape, floor)


def box_sizing(surf: Surface, n: int = 4001) -> dict:
    """Spanwise box dimensions (m) of ``surf``: chord, width, spar heights, mean depth, cover thickness
    (smeared, each cover), skin thickness and web thickness, from its mass budget."""
    eta = np.linspace(0.0, 1.0, n)
    c = surf.root_chord * (1.0 - (1.0 - surf.taper) * eta)
    width = (surf.rear_spar - surf.front_spar) * c
    xs = np.linspace(surf.front_spar, surf.rear_spar, 201)
    mean_depth = float(np.trapezoid(naca_thickness(xs, surf.thickness_ratio), xs) / (xs[-1] - xs[0])) * c
    h_fs = float(naca_thickness(surf.front_spar, surf.thickness_ratio)) * c
    h_rs = float(naca_thickness(surf.rear_spar, surf.thickness_ratio)) * c
    shear, moment = schrenk_shear_moment(eta, surf.taper)
    density = AL_DENSITY if surf.material == "aluminium" else CFRP_DENSITY
    m = surf.structural_mass_lb * LB
    # covers: two per box, `halves` boxes; the bending lever depends on the cover thickness (fixed point)
    t_cov = np.zeros(n)
    for _ in range(30):
        lever = mean_depth - t_cov
        area = _budget(
            moment / lever,
            MIN_COVER[surf.material] * width,
            surf.semispan,
            COVER_FRACTION * m / (2 * surf.halves * density),
        )
        t_cov = area / width
    web_height = h_fs + h_rs
    # webs: volume per unit span = t_web (h_fs + h_rs); fully stressed t_web ∝ V/(h_fs + h_rs)
    web_area = _budget(
        shear, MIN_WEB[surf.material] * web_height, surf.semispan, WEB_FRACTION * m / (surf.halves * density)
    )
    t_web = web_area / web_height
    return dict(
        eta=eta,
        chord=c,
        width=width,
        mean_depth=mean_depth,
        h_fs=h_fs,
        h_rs=h_rs,
        lever=mean_depth - t_cov,
        cover_area=t_cov * width,
        t_cover=t_cov,
        t_skin=SKIN_FRACTION * t_cov,
        t_web=t_web,
    )


def station_allowables(surf: Surface, eta_s: float, box: dict | None = None) -> dict:
    """Limit and ultimate allowables (N, N·m; bending as (negative, positive)) at span fraction ``eta_s``."""
    box = box or box_sizing(surf)
    at = {k: float(np.interp(eta_s, box["eta"], v)) for k, v in box.items() if isinstance(v, np.ndarray) and k != "eta"}
    area, lever = at["cover_area"], at["lever"]
    webs = at["h_fs"] + at["h_rs"]
    enclosed = at["mean_depth"] * at["width"]
    out = dict(
        chord=at["chord"],
        width=at["width"],
        depth=at["mean_depth"],
        lever=lever,
        t_cover=at["t_cover"],
        t_skin=at["t_skin"],
        t_web=at["t_web"],
        h_fs=at["h_fs"],
        h_rs=at["h_rs"],
    )
    if surf.material == "aluminium":
        up, low, web = AL["7055-T7751 (upper cover)"], AL["2324-T39 (lower cover)"], AL["7050-T7451 (spar webs)"]
        # Farrar: a panel at its own strength σ = F² E t / L (σ = F √(N E / L) with N = σ t)
        panel = {k: FARRAR_F**2 * AL_E * at["t_cover"] / RIB_PITCH for k in ("upper", "lower")}
        comp_up, comp_low = min(up["Fcy"], panel["upper"]), min(low["Fcy"], panel["lower"])
        sig = {
            "limit": {"positive": min(up["Fcy"], comp_up, low["Fty"]), "negative": min(up["Fty"], comp_low)},
            "ultimate": {"positive": min(comp_up, low["Ftu"]), "negative": min(up["Ftu"], comp_low)},
        }
        tau_web = {"limit": SHEAR_YIELD * web["Fty"], "ultimate": web["Fsu"]}
        tau_skin = {"limit": SHEAR_YIELD * min(up["Fty"], low["Fty"]), "ultimate": min(up["Fsu"], low["Fsu"])}
        out["panel_stress_MPa"] = panel
    else:
        e_cov, g_cov = laminate_moduli(COVER_LAYUP)
        _, g_web = laminate_moduli(WEB_LAYUP)
        eps = min(STRAIN_ULTIMATE["compression"], STRAIN_ULTIMATE["tension"])  # one cover is in compression
        panel_strain = FARRAR_F**2 * at["t_cover"] / RIB_PITCH
        s = e_cov * min(eps, panel_strain)
        sig = {"limit": {"positive": s, "negative": s}, "ultimate": {"positive": s, "negative": s}}
        tau_web = {k: g_web * STRAIN_ULTIMATE["shear"] for k in ("limit", "ultimate")}
        tau_skin = {k: g_cov * STRAIN_ULTIMATE["shear"] for k in ("limit", "ultimate")}
        out["laminate_MPa"] = dict(E_cover=e_cov, G_cover=g_cov, G_web=g_web)
        out["panel_strain"] = panel_strain
    for which in ("limit", "ultimate"):
        out[which] = dict(
            shear=tau_web[which] * MPA * at["t_web"] * webs,
            bending={k: v * MPA * area * lever for k, v in sig[which].items()},
            torsion=2.0 * enclosed * min(tau_web[which] * at["t_web"], tau_skin[which] * at["t_skin"]) * MPA,
        )
    return out


def derived_capabilities() -> dict:
    """{(surface, station): allowables} for every declared station of the baseline."""
    out = {}
    for surf in SURFACES:
        box = box_sizing(surf)
        for name, eta in surf.stations:
            out[(surf.name, name)] = station_allowables(surf, eta, box)
    return out


# --------------------------------------------------------------------------- tests


@pytest.fixture(scope="module")
def derived():
    return derived_capabilities()


def test_inputs_match_the_aircraft_file(baseline):
    """The documented planform, thickness ratios and structural masses are the aircraft file's."""
    a = baseline.model
    g, comps = a.geometry, {c.name: c.mass for c in a.mass.components}
    for surf, geo, comp in (
        (SURFACES[0], g.wing, "wing"),
        (SURFACES[1], g.horizontal_tail, "horizontal tail"),
        (SURFACES[2], g.vertical_tail, "vertical tail"),
    ):
        assert geo.area == pytest.approx(surf.area_ft2 * FT**2, rel=1e-6)
        assert geo.aspect_ratio == pytest.approx(surf.aspect_ratio) and geo.taper == pytest.approx(surf.taper)
        assert geo.thickness_ratio == pytest.approx(surf.thickness_ratio)
        assert comps[comp] == pytest.approx(surf.structural_mass_lb * LB, rel=1e-6)
    assert g.fuselage.width == pytest.approx(2 * FUSELAGE_HALF_WIDTH_FT * FT)
    assert SURFACES[0].root_chord == pytest.approx(40.08 * FT, rel=1e-3)  # docs/baseline-sources.md: c_r 40.08 ft


def test_mass_budget_closes():
    """The sized covers and webs weigh the declared fractions of each surface's structural mass."""
    for surf in SURFACES:
        box = box_sizing(surf)
        rho = AL_DENSITY if surf.material == "aluminium" else CFRP_DENSITY
        covers = 2 * surf.halves * rho * surf.semispan * np.trapezoid(box["cover_area"], box["eta"])
        webs = surf.halves * rho * surf.semispan * np.trapezoid(box["t_web"] * (box["h_fs"] + box["h_rs"]), box["eta"])
        assert covers == pytest.approx(COVER_FRACTION * surf.structural_mass_lb * LB, rel=1e-4)
        assert webs == pytest.approx(WEB_FRACTION * surf.structural_mass_lb * LB, rel=1e-4)


def test_hand_check_of_the_wing_root_bending(derived):
    """Hand arithmetic at the wing root, independent of station_allowables: NACA 4-digit half-thickness
    y_t/t = 5 (0.2969 √x − 0.1260 x − …) gives spar heights 0.8909 t (15 % c) and 0.7606 t (60 % c);
    M_limit,positive = Fty(2324-T39) × A_cover × lever, M_ultimate,positive = Ftu(2324-T39) × A × lever."""
    a = derived[("wing", "root")]
    t = 0.11 * 40.08 * FT
    assert a["h_fs"] == pytest.approx(0.8909 * t, rel=2e-3) and a["h_rs"] == pytest.approx(0.7606 * t, rel=2e-3)
    area = a["t_cover"] * a["width"]
    assert a["limit"]["bending"]["positive"] == pytest.approx(393e6 * area * a["lever"], rel=1e-9)
    assert a["ultimate"]["bending"]["positive"] == pytest.approx(476e6 * area * a["lever"], rel=1e-9)
    assert a["width"] == pytest.approx(0.45 * 40.08 * FT, rel=1e-3)


def test_laminate_moduli_by_hand():
    """Quasi-isotropic check of the lamination code: a [0/±45/90] 25 % each laminate has
    E = (U1² − U4²)/U1 and G = (U1 − U4)/2 with U1 = (3Q11 + 3Q22 + 2Q12 + 4Q66)/8, U4 = (Q11 + Q22 + 6Q12 − 4Q66)/8."""
    e1, e2, g12, nu12 = PLY["E1"], PLY["E2"], PLY["G12"], PLY["nu12"]
    d = 1 - nu12**2 * e2 / e1
    q11, q22, q12, q66 = e1 / d, e2 / d, nu12 * e2 / d, g12
    u1 = (3 * q11 + 3 * q22 + 2 * q12 + 4 * q66) / 8
    u4 = (q11 + q22 + 6 * q12 - 4 * q66) / 8
    e, g = laminate_moduli({0: 0.25, 45: 0.25, -45: 0.25, 90: 0.25})
    assert e == pytest.approx((u1**2 - u4**2) / u1, rel=1e-9) and g == pytest.approx((u1 - u4) / 2, rel=1e-9)


def test_declared_capability_matches_the_derivation(baseline, derived):
    """Every declared allowable of aircraft/lta.yaml is the derivation's within 1 %, and every derived
    station and quantity is declared."""
    st = baseline.model.structure
    assert st is not None
    seen = set()
    for surface in ("wing", "horizontal_tail", "vertical_tail"):
        for cap in getattr(st, surface):
            station = cap.station if isinstance(cap.station, str) else f"{float(cap.station):g}"
            a = derived[(surface, station)]
            for which in ("limit", "ultimate"):
                expected, declared = a[which][cap.quantity], getattr(cap, which)
                expected = (
                    (expected["negative"], expected["positive"]) if isinstance(expected, dict) else (expected,) * 2
                )
                declared = (
                    (declared.negative, declared.positive) if hasattr(declared, "negative") else (float(declared),) * 2
                )
                assert declared == pytest.approx(expected, rel=0.01), (surface, station, cap.quantity, which)
            assert "[research §10]" in cap.source
            seen.add((surface, station, cap.quantity))
    assert seen == {(k[0], k[1], q) for k in derived for q in ("shear", "bending", "torsion")}


# --------------------------------------------------------------------------- the table of §10


def _fmt(v, unit):
    if isinstance(v, dict):
        return f"−{v['negative'] / unit:,.0f} / +{v['positive'] / unit:,.0f}"
    return f"{v / unit:,.0f}"


def main():
    d = derived_capabilities()
    print(
        "| surface | station | chord m | box w × d m | lever m | cover t mm (skin) | web t mm | "
        "shear kN lim / ult | bending kN·m lim (−/+) | bending kN·m ult (−/+) | torsion kN·m lim / ult |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for (surface, station), a in d.items():
        print(
            f"| {surface} | {station} | {a['chord']:.2f} | {a['width']:.2f} × {a['depth']:.3f} | {a['lever']:.3f} | "
            f"{a['t_cover'] * 1e3:.1f} ({a['t_skin'] * 1e3:.1f}) | {a['t_web'] * 1e3:.1f} | "
            f"{a['limit']['shear'] / 1e3:,.0f} / {a['ultimate']['shear'] / 1e3:,.0f} | "
            f"{_fmt(a['limit']['bending'], 1e3)} | {_fmt(a['ultimate']['bending'], 1e3)} | "
            f"{a['limit']['torsion'] / 1e3:,.0f} / {a['ultimate']['torsion'] / 1e3:,.0f} |"
        )
    for (surface, station), a in d.items():
        extra = a.get("panel_stress_MPa") or {"panel strain": a.get("panel_strain"), **a.get("laminate_MPa", {})}
        print(surface, station, {k: round(float(v), 4) for k, v in extra.items()})


if __name__ == "__main__":
    main()
