"""The baseline's cruise drag against published values for its class.

References (numbers as recorded, with their sources, in docs/baseline-sources.md §7):
- NASA Common Research Model, AIAA CFD Drag Prediction Workshops at M 0.85, CL 0.500, Re_c 5 million
  (wind-tunnel Reynolds number): wing-body-tail CD ≈ 0.0270 (DPW-4, Vassberg et al., "Summary of the
  Fourth AIAA CFD Drag Prediction Workshop", AIAA 2010-4547, NTRS 20100025833), wing-body
  CD ≈ 0.0255 (DPW-5, Levy et al., J. Aircraft 51(4), 2014). No nacelles, pylons or fin.
- Boeing 777-200ER cruise L/D: no manufacturer figure is public. The Breguet range equation with
  the published range (7,530 nmi), weights and a GE90-94B cruise TSFC of 0.545 lb/lbf/h gives a
  mission-average L/D of 17.7; the test band is 18.5 ± 1 (docs/baseline-sources.md §7, [E]).
- CD0 ≈ 0.0153 (on 4,927.3 ft²) implied by L/D 18.5 and e = 0.85 at the mid-cruise CL (same §7, [E]).
- A published parasite-drag breakdown for a large twin (Obert 2009; Roskam Part VI; Raymer's
  examples) could not be consulted here; the breakdown test checks only internal consistency and
  the ordering every build-up of a tube-and-wing transport shows (wing first, fuselage second).
"""

import numpy as np
import pytest

from certkit import atmosphere as isa
from certkit.models.aero import drag

LB = 0.45359237
G0 = 9.80665
H_CRUISE = 35_000 * 0.3048
M_CRUISE = 0.84


def _mid_cruise_cl(aircraft, mass_lb=520_000.0):
    """CL at the mid-cruise weight of docs/baseline-sources.md §7 (520,000 lb), M 0.84, 35,000 ft."""
    q = 0.5 * isa.GAMMA * isa.pressure(H_CRUISE) * M_CRUISE**2
    return mass_lb * LB * G0 / (q * aircraft.reference.area)


@pytest.fixture(scope="module")
def cruise(baseline):
    ac = baseline.model
    cl = _mid_cruise_cl(ac)
    return ac, cl, drag.drag_buildup(ac, M_CRUISE, H_CRUISE, np.array([cl, 0.5]))


def test_mid_cruise_lift_coefficient(cruise):
    """CL at 520,000 lb, M 0.84, 35,000 ft is 0.428 in docs/baseline-sources.md §7 (the brief's
    'about 0.5' is the DPW design CL); tolerance 0.005."""
    _, cl, _ = cruise
    assert cl == pytest.approx(0.428, abs=0.005)


def test_cruise_cd0_against_the_class_estimate(cruise):
    """Build-up CD0 (incl. leakage/protuberances, without wave drag) vs 0.0153 at flight Reynolds
    number (≈ 6.6e6 per metre); tolerance ±15 % (the reference itself is a Breguet-derived
    estimate). Computed: 0.0142."""
    _, _, b = cruise
    assert float(b.CD0[0]) == pytest.approx(0.0153, rel=0.15)


def test_cruise_lift_to_drag_in_the_777_band(cruise):
    """L/D at the mid-cruise CL within 18.5 ± 1 (docs §7); computed 19.2 (CD 0.0223: CD0 0.0142,
    wave 0.0002, induced 0.0079 with Nita–Scholz e = 0.842). At CL 0.5 L/D must stay in the same
    band widened to 20.5 (the polar's maximum L/D lies near CL 0.6 for this CD0 and e)."""
    _, _, b = cruise
    ld = b.lift_to_drag
    assert 17.5 <= ld[0] <= 19.5
    assert 17.5 <= ld[1] <= 20.5
    assert float(b.CD_wave[0]) < 0.0005  # below drag divergence at cruise: a few counts at most


def _crm_like(baseline, names, cl=0.5, mach=0.85):
    ac = baseline.model
    parts = [c for c in drag.airframe_components(ac.geometry) if c.name in names]
    re_per_m = 5.0e6 / ac.reference.mean_chord
    return drag.drag_buildup(ac, mach, H_CRUISE, cl, components=parts, reynolds_per_metre_override=re_per_m)


def test_wing_body_tail_at_wind_tunnel_reynolds_vs_crm_dpw4(baseline):
    """Baseline wing + fuselage + horizontal tail at Re_c 5 million, M 0.85, CL 0.5 vs the CRM WBH
    CD ≈ 0.0270 (DPW-4). Tolerance ±10 %: the geometries differ (CRM: A 9.0, Λc/4 35°, its own
    fuselage; baseline: A 8.81, 30.9°), the CFD spread is about ±5 counts, and the CRM total is
    untrimmed at i_H = 0. Computed: 0.0282."""
    b = _crm_like(baseline, {"wing", "fuselage", "horizontal tail"})
    assert float(b.CD) == pytest.approx(0.0270, rel=0.10)


def test_wing_body_at_wind_tunnel_reynolds_vs_crm_dpw5(baseline):
    """Wing + fuselage at Re_c 5 million, M 0.85, CL 0.5 vs the CRM WB CD ≈ 0.0255 (DPW-5);
    tolerance ±10 % as above. Computed: 0.0259. The tail increment (WBH − WB) must be positive and
    below 30 counts (DPW: 10–15 counts)."""
    wb = _crm_like(baseline, {"wing", "fuselage"})
    wbh = _crm_like(baseline, {"wing", "fuselage", "horizontal tail"})
    assert float(wb.CD) == pytest.approx(0.0255, rel=0.10)
    assert 0.0 < float(wbh.CD - wb.CD) < 0.0030


def test_flight_reynolds_lowers_skin_friction_drag(baseline):
    """From Re_c 5 million to flight Re (≈ 55 million on c̄) every component's CD0 falls exactly as
    its Cf (form factors and wetted areas do not depend on Re; 1e-12). The WBH build-up falls from
    0.0167 to 0.0116, 51 counts: twice the 15–25 counts docs/baseline-sources.md §7 guessed ([E],
    unsourced), so that guess is not used as a criterion here (an open point of the report)."""
    ac = baseline.model
    parts = [c for c in drag.airframe_components(ac.geometry) if c.name in {"wing", "fuselage", "horizontal tail"}]
    tunnel = drag.parasite_drag(
        ac.geometry,
        ac.reference,
        0.85,
        H_CRUISE,
        components=parts,
        reynolds_per_metre_override=5.0e6 / ac.reference.mean_chord,
    )
    flight = drag.parasite_drag(ac.geometry, ac.reference, 0.85, H_CRUISE, components=parts)
    for t, f in zip(tunnel.components, flight.components):
        assert f.CD0 / t.CD0 == pytest.approx(f.skin_friction / t.skin_friction, rel=1e-12)
    assert float(tunnel.CD0 - flight.CD0) == pytest.approx(0.0051, abs=0.0003)


def test_parasite_breakdown_is_consistent(cruise):
    """The breakdown table sums to CD0 (1e-12), every wetted component's row has S_wet, Re, Cf, FF, Q, and the wing
    and fuselage are the two largest contributions, together more than 60 % (no published
    breakdown was available to compare the shares with; see the module docstring)."""
    ac, _, b = cruise
    table = b.parasite.breakdown(0)
    assert table["CD0"].sum() == pytest.approx(float(b.CD0[0]), rel=1e-12)
    parts = table[~table["name"].isin(["leakage and protuberances", "fuselage upsweep"])]
    assert parts[["S_wet", "Re", "Cf", "FF", "Q"]].notna().all().all()
    ranked = parts.sort_values("CD0", ascending=False)["name"].tolist()
    assert ranked[:2] == ["wing", "fuselage"]
    assert parts.set_index("name").loc[["wing", "fuselage"], "share"].sum() > 0.60
