"""The baseline's directional and roll derivatives against the Boeing 747's published ones.

References (no one here wrote them):
* Boeing 747-100, power approach, sea level, M ≈ 0.2 (Heffley & Jewell, *Aircraft Handling Qualities Data*, NASA
  CR-2144, 1972, as tabulated by Roskam, *Airplane Flight Dynamics and Automatic Flight Controls*, Part I, App. B;
  S 5,500 ft², b 196 ft): CY_β −1.08, Cn_β 0.184, Cl_β −0.281, Cn_δr −0.113, CY_δr 0.179, Cl_δa 0.053 (per rad),
  Cm_α̇ −3.3.
* Boeing 747, M 0.8, 40,000 ft (Etkin & Reid, *Dynamics of Flight*, 3rd ed., §6.2/§6.8, from CR-2144; data in
  ``tests/dynamics/b747_etkin.py``): CY_β −0.877, Cn_β 0.195, Cl_β −0.280, Cn_δr −0.1257, CY_δr 0.1146.
* 747 vertical-tail area 829.5 ft²: JSBSim's B747 model (``aircraft/B747/B747.xml``, metrics ``vtailarea``), the
  peer tool's data.

The two airplanes differ in size and fin: the fin-dominated derivatives are compared per unit of fin area
(coefficient × S/S_v; the baseline's S_v is the declared 527.84 ft²), which removes the fin-size difference and
leaves the fin's effectiveness and lever; tolerance ±30 % (the levers l_v/b differ: the baseline's is 0.41, and
the 747's own rudder lever Cn_δr/CY_δr · b is 0.63 b at approach). Cl_β is a wing derivative and is compared as
is, ±30 %. Where the baseline falls outside, the test is an expected failure naming the cause (a model limit or the
declared data), never a wider band: it fails loudly (strict) when the cause is fixed.
"""

import pytest

S_747, B_747, SV_747 = 5500.0, 196.0, 829.5  # ft²; ft; ft² (JSBSim B747 vtailarea)
SV_BASE, S_BASE = 527.84, 4927.3  # ft², aircraft/lta.yaml
BAND = 0.30

APPROACH_747 = {
    "CY_beta": -1.08,
    "Cn_beta": 0.184,
    "Cl_beta": -0.281,
    "Cn_rudder": -0.113,
    "CY_rudder": 0.179,
    "Cl_aileron": 0.053,
}
CRUISE_747 = {"CY_beta": -0.877, "Cn_beta": 0.195, "Cl_beta": -0.280, "Cn_rudder": -0.1257, "CY_rudder": 0.1146}
PER_FIN_AREA = ("CY_beta", "Cn_beta", "Cn_rudder", "CY_rudder")


@pytest.fixture(scope="module")
def model(baseline):
    from certkit.engine.context import Context

    ctx = Context(baseline)
    return {"takeoff": ctx.aero("takeoff").model, "clean": ctx.aero("clean").model}


def ratio(model, config, mach, name, ref):
    """The baseline's derivative over the 747's, per unit of fin area for the fin-dominated ones (signs compared
    in magnitude: certkit's aileron sign is Etkin & Reid's, Roskam's table the opposite)."""
    ours = abs(float(model[config].derivative(name, mach)))
    theirs = abs(ref[name])
    if name in PER_FIN_AREA:
        ours, theirs = ours * S_BASE / SV_BASE, theirs * S_747 / SV_747
    return ours / theirs


@pytest.mark.parametrize("name", ["CY_beta", "Cn_beta", "Cn_rudder"])
def test_fin_derivatives_per_fin_area_at_approach(model, name):
    """Per unit fin area at M 0.2: CY_β 0.79, Cn_β 0.73 and Cn_δr 1.03 of the 747's. Cn_β is near the band's low
    end: the fuselage's destabilising Cn_β (Raymer eq. 16.50) is taken whole and the fin has no fuselage sidewash
    gain (DATCOM (1 + dσ/dβ) η_v ≈ 1.1) nor the low-wing body side force (K_i = 1, certkit/models/aero/fuselage.py)."""
    assert ratio(model, "takeoff", 0.2, name, APPROACH_747) == pytest.approx(1.0, abs=BAND)


@pytest.mark.parametrize("name", ["CY_beta", "Cn_beta", "Cn_rudder"])
def test_fin_derivatives_per_fin_area_at_cruise(model, name):
    """Per unit fin area at M 0.8 (Etkin's 40,000 ft case): CY_β 1.11, Cn_β 0.89, Cn_δr 1.14 of the 747's."""
    assert ratio(model, "clean", 0.8, name, CRUISE_747) == pytest.approx(1.0, abs=BAND)


@pytest.mark.xfail(
    strict=True,
    reason="CY_δr per fin area 1.48 × the 747's at approach (2.85 × at M 0.8, where the "
    "747's rudder ratio changer limits it): the lattice is inviscid (no DATCOM viscous factor ≈ 0.8 on "
    "the flap effectiveness) and the rudder's side force sits on a shorter lever (0.44 b against the "
    "747's 0.63 b) — its yawing moment per fin area, Cn_δr, matches: docs/baseline-sources.md §14",
)
def test_rudder_side_force_per_fin_area(model):
    assert ratio(model, "takeoff", 0.2, "CY_rudder", APPROACH_747) == pytest.approx(1.0, abs=BAND)


@pytest.mark.xfail(
    strict=True,
    reason="Cl_β at M 0.8: −0.192 against the 747's −0.280 (0.69): the model's Cl_β is the lattice's at α = 0 "
    "(CL 0.20 with the declared linear twist) and does not grow with the lift coefficient; the lattice's own Cl_β "
    "grows by −0.087 per unit CL at M 0.8, which at the 747's cruise CL 0.654 (W/q̄S, Etkin & Reid Table 6.2) gives "
    "−0.231 (0.82); the baseline's 31° of sweep against the 747's 37.5° accounts for the rest (Roskam Part VI "
    "§10.2.4.1). A named model limit, docs/baseline-sources.md §14 (with that growth in the flight model the "
    "declared roll control, the outboard aileron alone, cannot hold §25.177(c)'s sideslips: it waits for the "
    "flaperons and spoilers)",
)
def test_dihedral_effect_at_cruise(model):
    """Cl_β at M 0.8 against the 747's −0.280 at its cruise lift coefficient."""
    assert ratio(model, "clean", 0.8, "Cl_beta", CRUISE_747) == pytest.approx(1.0, abs=BAND)


@pytest.mark.xfail(
    strict=True,
    reason="Cl_β at approach 0.55 × the 747's (−0.154 against −0.281 at CL 1.76): the "
    "model's Cl_β is the lattice's at one angle of attack and does not grow with the lift coefficient "
    "as a swept wing's does (ΔCl_β/CL ∝ sin 2Λ; the lattice's −0.081 per unit CL at M 0.2 gives 1.01 × the "
    "747's): a named model limit, docs/baseline-sources.md §14",
)
def test_dihedral_effect_at_approach(model):
    assert ratio(model, "takeoff", 0.2, "Cl_beta", APPROACH_747) == pytest.approx(1.0, abs=BAND)


@pytest.mark.xfail(
    strict=True,
    reason="Cl_δa 1.38 × the 747's 0.053 per rad at approach: the lattice's control "
    "effectiveness is inviscid (DATCOM's viscous factor ≈ 0.8 would give about 1.07): a named model "
    "limit, docs/baseline-sources.md §14",
)
def test_roll_control_power(model):
    assert ratio(model, "takeoff", 0.2, "Cl_aileron", APPROACH_747) == pytest.approx(1.0, abs=BAND)


@pytest.mark.xfail(
    strict=True,
    reason="Cm_α̇ at M 0.8: −9.94 against the 747's −6.41 (1.55 ×), at M 0.2 −6.20 against "
    "−3.3 (1.9 ×). The method is the textbook quasi-steady downwash lag (Etkin & Reid ch. 5, Roskam Part "
    "I ch. 4), implemented as written; the same formula with the 747's own tail (JSBSim B747: S_t "
    "1,469.6 ft², l_t 106.6 ft; a_t ≈ 3.9/rad and dε/dα ≈ 0.45 estimated, η 0.9–1) gives −13 to −14 at M 0.8, twice "
    "the 747's "
    "published value: the gap is the quasi-steady theory's against flight-derived data (the wing's own "
    "α̇ lift and the bound vorticity's unlagged share of the tail downwash are not in it), not an error "
    "of the implementation; §25.181 does not depend on it (tests/rules/test_r25_181.py). "
    "docs/baseline-sources.md §5a",
)
@pytest.mark.parametrize("mach, published", [(0.8, -6.41), (0.2, -3.3)])
def test_downwash_lag_pitch_damping(model, mach, published):
    """Cm_α̇ (per unit α̇c̄/2V) against the 747's (Heffley & Jewell, CR-2144: −6.41 at M 0.8; −3.3 in power approach),
    both on their own wing's reference chord; ±30 %."""
    _, cm_ad = model["clean"].alpha_dot_derivatives(mach)
    assert float(cm_ad) / published == pytest.approx(1.0, abs=BAND)
