"""The tail's share of the flap increments and the downwash-lag terms in the per-configuration model the trims use."""

import textwrap

import numpy as np
import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.models.aero.high_lift import FlapSettings, lift_and_moment_increment

from ..conftest import BASELINE


def _tail_off(aircraft, configuration, cl_alpha):
    """Raymer's tail-off flap increments (eq. 12.22 and the centre of the flap load at half chord)."""
    w, r = aircraft.geometry.wing, aircraft.reference
    return lift_and_moment_increment(
        w,
        w.flaps,
        aircraft.configurations[configuration].flap,
        cl_alpha,
        r.moment_point.x,
        r.mean_chord,
        FlapSettings.of(aircraft.configurations),
    )


@pytest.fixture(scope="module")
def baseline_context():
    return Context(load_aircraft(BASELINE))


def test_flaps_down_moment_is_tail_on(baseline_context):
    """The flap's downwash at the tail lifts less on the tail (ΔC_L,t < 0) and pitches the airplane nose-up: the
    tail-on flap moment the trims see is less nose-down than the tail-off estimate, and the tail-on lift
    increment a little smaller, in every flap setting (the sign every transport's tail-on/tail-off runs show,
    Perkins & Hage, Airplane Performance, Stability and Control, 1949, ch. 5 on the flaps' downwash at the tail)."""
    ctx = baseline_context
    clean = ctx.aero("clean").table
    for name in ("takeoff", "approach", "landing"):
        aero = ctx.aero(name)
        d_cl, d_cm = _tail_off(ctx.aircraft, name, aero.table["CL_alpha"][0])
        tail_cl = aero.table["CL0"][0] - clean["CL0"][0] - d_cl
        tail_cm = aero.table["Cm0"][0] - clean["Cm0"][0] - d_cm
        assert d_cm < 0 < tail_cm < -d_cm, name
        assert -0.1 * d_cl < tail_cl < 0, name
        assert any("tail share of the flap increments from the change of downwash" in n for n in aero.notes)
    assert "tail share" not in " ".join(ctx.aero("clean").notes)


def test_declared_tail_share_replaces_the_lattice_estimate(tmp_path):
    """configurations.<name>.tail_flap_increment (e.g. wind-tunnel tail-on minus tail-off) is added as declared."""
    text = BASELINE.read_text().replace(
        "    delta_CD0: 0.0120\n",
        "    delta_CD0: 0.0120\n    tail_flap_increment: {delta_CL: -0.02, delta_Cm: 0.05, source: test entry}\n",
    )
    f = tmp_path / "declared.yaml"
    f.write_text(text)
    ctx = Context(load_aircraft(f))
    clean, takeoff = ctx.aero("clean").table, ctx.aero("takeoff")
    d_cl, d_cm = _tail_off(ctx.aircraft, "takeoff", takeoff.table["CL_alpha"][0])
    assert takeoff.table["Cm0"][0] == pytest.approx(clean["Cm0"][0] + d_cm + 0.05, abs=1e-12)
    assert takeoff.table["CL0"][0] == pytest.approx(clean["CL0"][0] + d_cl - 0.02, abs=1e-12)
    assert any("declared" in n and "test entry" in n for n in takeoff.notes)


def test_alpha_dot_terms_reach_the_model_and_can_be_overridden(tmp_path, baseline_context):
    """The lattice's C_Lα̇, C_mα̇ are in the flight model (the equations of motion take them from
    ``alpha_dot_derivatives``); aerodynamics.overrides replaces them like any other estimate."""
    model = baseline_context.aero("clean").model
    cl_ad, cm_ad = model.alpha_dot_derivatives(0.5)
    assert cl_ad > 0 > cm_ad
    f = tmp_path / "o.yaml"
    f.write_text(
        BASELINE.read_text()
        + textwrap.dedent("""
        aerodynamics:
          overrides_source: flight-test match (test)
          overrides:
            clean: {Cm_alphadot: -4.0, CL_alphadot: 1.5}
    """)
    )
    aero = Context(load_aircraft(f)).aero("clean")
    assert tuple(float(v) for v in aero.model.alpha_dot_derivatives(0.5)) == (1.5, -4.0)
    assert aero.overrides["Cm_alphadot"]["estimate"] is not None


def test_declared_derivative_tables_keep_their_alpha_dot_terms(tmp_path):
    """An airplane that declares its derivatives gets no estimated α̇ terms: zero when the table has none."""
    text = BASELINE.read_text()
    start, end = text.index("geometry:\n"), text.index("mass:\n")
    f = tmp_path / "tables.yaml"
    f.write_text(
        text[:start]
        + text[end:]
        + textwrap.dedent("""
        aerodynamics:
          derivative_tables:
            clean:
              source: test data
              mach: [0.25, 0.9]
              derivatives: {CL0: 0.3, CL_alpha: 5.0, Cm_alpha: -1.2, Cm_q: -20.0, CD0: 0.018, k: 0.045}
    """)
    )
    model = Context(load_aircraft(f)).aero("clean").model
    assert np.allclose(model.alpha_dot_derivatives(0.5), 0.0)


def test_tail_share_without_flaps_is_an_input_error(tmp_path):
    """A tail share declared on a configuration without flaps would be ignored: an error naming the YAML path,
    line and the flap angle, reported at load."""
    from certkit.errors import InputError

    text = BASELINE.read_text().replace(
        '    source: "[given]"\n',
        '    source: "[given]"\n    tail_flap_increment: {delta_CL: -0.02, delta_Cm: 0.05, source: test entry}\n',
        1,
    )
    f = tmp_path / "clean_share.yaml"
    f.write_text(text)
    with pytest.raises(
        InputError, match=r"clean_share.yaml:\d+: configurations\.clean\.tail_flap_increment: .*flap 0 deg"
    ):
        load_aircraft(f)
