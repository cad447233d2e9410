"""The baseline's declared performance calibration (aircraft/lta.yaml ``calibration:``, docs/baseline-sources.md §7a).

References: Raymer, *Aircraft Design: A Conceptual Approach*, 6th ed., eq. 12.36 (upsweep drag area
3.83 u^2.5 A_max); the declared cruise TSFC (York, Hoburg & Drela 2018, GE90-94B at 35,000 ft, M 0.80:
0.526 lb/lbf/h); the declared design-range target (7,530 nmi, 305 passengers [given]). The recomputation test
solves the drag factor again: it fails when a model change moves the baseline off its target, so that the factor
is re-solved (``certkit calibrate``) instead of going stale in the file.
"""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

from certkit.design.calibration import solve_drag_factor, with_drag_factor
from certkit.models.aero import drag
from certkit.models.aero.airplane import DEFAULT_MACHS, drag_terms
from certkit.models.performance.fuel_flow import EngineFuel
from certkit.units import FT, G0

LB_PER_LBF_H = 1.0 / (3600.0 * G0)  # 1 lb/lbf/h in kg/(N s)


def test_upsweep_drag_is_raymer_eq_12_36(baseline):
    """The declared 6° upsweep adds Raymer's D/q = 3.83 u^2.5 A_max to CD0 (with the 3 % leakage and protuberance
    allowance on it): 0.1047 rad, A_max = π/4 · 20.76 · 20.23 ft² = 30.64 m² → D/q 0.416 m², ΔCD0 = 0.00094 on
    457.76 m² (hand values to 2 %); no term without a declared upsweep."""
    ac = baseline.model
    flat = ac.model_copy(
        update={
            "geometry": ac.geometry.model_copy(
                update={"fuselage": ac.geometry.fuselage.model_copy(update={"upsweep": None})}
            )
        }
    )
    with_up = drag.parasite_drag(ac.geometry, ac.reference, 0.84, 35000 * FT)
    without = drag.parasite_drag(flat.geometry, flat.reference, 0.84, 35000 * FT)
    assert without.upsweep == 0.0
    assert with_up.upsweep * ac.reference.area == pytest.approx(0.416, rel=0.02)
    assert float(with_up.CD0 - without.CD0) == pytest.approx(0.00094, rel=0.02)


def test_drag_factor_scales_the_zero_lift_drag_only(baseline):
    """CD0 of the clean table is the build-up's times the declared factor, k (induced drag) is not scaled; the takeoff
    configuration's declared ΔCD0 (0.0120) is added unscaled."""
    ac = baseline.model
    f = ac.calibration.drag_factor
    cd0, k, notes = drag_terms(ac, DEFAULT_MACHS)
    cd0_1, k_1, _ = drag_terms(with_drag_factor(ac, 1.0), DEFAULT_MACHS)
    assert np.allclose(np.array(cd0) / np.array(cd0_1), f, rtol=1e-12)
    assert np.allclose(np.array(k), np.array(k_1), rtol=1e-12)
    assert any("calibration" in n for n in notes)
    from certkit.models.aero.airplane import build_airplane_aero, lattice_derivatives

    lattice = lattice_derivatives(ac)
    clean = build_airplane_aero(ac, "clean", lattice=lattice).table["CD0"]
    takeoff = build_airplane_aero(ac, "takeoff", lattice=lattice).table["CD0"]
    assert np.allclose(np.array(takeoff) - np.array(clean), 0.0120, atol=1e-12)


def test_fuel_flow_factor_applies_once_on_the_declared_tsfc(baseline):
    """At the declared TSFC condition (35,000 ft, M 0.80) the installed fuel flow per thrust is the declared
    uninstalled 0.526 lb/lbf/h times the installation factor 1.03 (0.5418): a factor applied twice or not at all
    fails."""
    fuel = EngineFuel.of(baseline.model)
    tsfc = float(fuel.tsfc(35000 * FT, 0.80)) / LB_PER_LBF_H
    assert tsfc == pytest.approx(0.526 * 1.03, rel=1e-6)
    assert any("installation" in n for n in fuel.notes)


def test_declared_drag_factor_is_the_solved_one(baseline):
    """``solve_drag_factor`` from the declared value finds it again (the file holds the factor, rounded down to 4
    decimals, that reaches the 7,530 nmi target): the range it gives lies within 0.05 % above the target. A model
    change that moves the range fails here first — re-run ``certkit calibrate aircraft/lta.yaml``."""
    ac = baseline.model
    result = solve_drag_factor(ac)
    assert result.factor == pytest.approx(ac.calibration.drag_factor, abs=1.5e-4)
    assert 0.0 <= result.error < 5e-4
    assert result.achieved / 1852 == pytest.approx(7530, rel=5e-4)


def test_calibration_needs_a_target(tmp_path):
    """``certkit calibrate`` on a file without a calibration target: exit 2, the YAML path named, no traceback."""
    data = yaml.safe_load(Path("aircraft/lta.yaml").read_text())
    del data["calibration"]["target"]
    path = tmp_path / "no_target.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    out = subprocess.run([sys.executable, "-m", "certkit.cli", "calibrate", str(path)], capture_output=True, text=True)
    assert out.returncode == 2
    assert "calibration.target" in out.stderr and "Traceback" not in out.stderr


def test_tail_calibration_needs_the_declared_component(baseline):
    """The tail calibration's target is the declared 'horizontal tail' component (5,800 lb); a file without one is a
    user error naming mass.components."""
    from certkit.design.calibration import declared_tail_mass
    from certkit.errors import UserError

    ac = baseline.model
    assert declared_tail_mass(ac) == pytest.approx(5800 * 0.45359237)
    others = [c for c in ac.mass.components if c.name != "horizontal tail"]
    without = ac.model_copy(update={"mass": ac.mass.model_copy(update={"components": others})})
    with pytest.raises(UserError, match="mass.components"):
        declared_tail_mass(without)
