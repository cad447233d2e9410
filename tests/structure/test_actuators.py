"""Elevator actuator sizing (certkit.models.structure.actuators): hand arithmetic with the baseline's declared
data (2 per panel, 3,000 psi, arm 0.20 m, margin 1.25, share 1, 40 deg/s, travel −30°/+25°).
Unit constants written out independently: 1 psi = 6894.757 Pa, 1 US gal = 231 in³ = 3.785412 L."""

from __future__ import annotations

import math

import pytest

from certkit.models.structure.actuators import size_elevator_actuators

PSI = 6894.757
GAL = 231 * 0.0254**3


def test_hand_arithmetic(baseline):
    """H = 200 kN·m for both panels: 100 kN·m per panel over a 0.2 m arm = 500 kN, stall 625 kN; piston area
    625e3 / (3000 psi) = 302.2 cm²; stroke 0.2 (sin 25° + sin 30°) = 184.5 mm; flow A · 0.2 m · 40°/s =
    4.219e-3 m³/s = 253.1 L/min = 66.87 gpm per actuator. Tolerance 1e-4 (rounded hand values 1e-3)."""
    r = size_elevator_actuators(baseline.model, 200e3)
    assert r.count == 4
    assert r.stall_force == pytest.approx(625e3, rel=1e-9)
    area = 625e3 / (3000 * PSI)
    assert r.piston_area == pytest.approx(area, rel=1e-4) and r.piston_area * 1e4 == pytest.approx(302.2, rel=1e-3)
    assert r.stroke == pytest.approx(0.2 * (math.sin(math.radians(25)) + math.sin(math.radians(30))), rel=1e-9)
    flow = area * 0.2 * math.radians(40)
    assert r.flow == pytest.approx(flow, rel=1e-4)
    assert r.flow_l_per_min == pytest.approx(flow * 60e3, rel=1e-4)
    assert r.flow_gpm == pytest.approx(flow / GAL * 60, rel=1e-4) and r.flow_gpm == pytest.approx(66.87, rel=1e-3)
    assert r.mass == pytest.approx(8.0 + 1.6e-4 * 625e3 * r.stroke, rel=1e-9)


def test_flow_is_independent_of_the_arm(baseline):
    """Q = A r δ̇ = margin · share · (H/2) · δ̇ / p: the arm cancels (hand: 1.25 × 100e3 × 0.6981 / 20.684e6)."""
    r = size_elevator_actuators(baseline.model, 200e3)
    assert r.flow == pytest.approx(1.25 * 100e3 * math.radians(40) / (3000 * PSI), rel=1e-4)


def test_positions_on_the_hinge_line(baseline):
    """Four actuators, two per panel, mirror images, aft of the tail's root leading edge."""
    r = size_elevator_actuators(baseline.model, 100e3)
    ys = sorted(p[1] for p in r.positions)
    assert len(ys) == 4 and ys[0] == pytest.approx(-ys[-1]) and ys[1] == pytest.approx(-ys[2])
    assert all(p[0] > baseline.model.geometry.horizontal_tail.root_leading_edge.x for p in r.positions)
    assert len(r.components()) == 4
