"""§25.331(b) Maneuvering balanced conditions: the airplane in equilibrium with zero pitching acceleration at the
points of the §25.333(b) manoeuvring envelope, flaps retracted, and at the §25.345(a) flap-extended load factors at
the flap speeds; wing and horizontal-tail loads from the same trimmed state (strip loads model), compared with the
declared structural capability (§25.303, §25.305).

The envelope corners are those of §25.333 (:func:`certkit.models.loads.vn_envelope.envelope`, with its
C_N,max criterion): A on the +C_N,max line at n₊, D (VD, n₊), E (VD, 0), F (VC, n₋), H on the −C_N,max line at n₋,
and the point at VC on the n₊ line. The figure of §25.333(b) is not verified (docs/regulation-notes.md §1): the
paragraph names "A through I"; points whose letters could not be read (C, G, I) are not assumed, the VC point on the
n₊ line is named by its speed. The balanced state itself is :mod:`certkit.models.loads.balanced` (steady pull-up or
push-over at n, linear lift up to C_N,max).

Flaps extended (every configuration other than ``clean``): n = the declared ``envelope.limit_load_factors.
flaps_extended`` (else 2.0, §25.345(a)(1)) and n = 0 at the design flap speed VF: the larger of the declared placard
VFE and the §25.335(e)(3) minimum (1.6 VS1 takeoff flaps at MTOW, 1.8 VS1 approach and landing flaps at MLW). The
strip loads model's lattice carries the wing's flap as a control: the configuration's flap lift (tail off) is spread
on the wing's strips with the lattice's flap distribution and the tail's share (the change of downwash) on the
tail's (:func:`certkit.models.loads.response.flap_deflection`), so both surfaces are evaluated flaps extended.

Out of trim (§25.331(a)(2): "The in-trim and out-of-trim flight conditions specified in § 25.255 must be considered";
text from the current eCFR via law.cornell.edu, docs/regulation-notes.md): with a movable stabiliser and its trim
rate declared, the clean points at VC and VD (VC on the n₊ line, D, E, F — the speeds of §25.255's manoeuvres) are
evaluated again with the stabiliser of a 1 g trim at the lower of the point's speed and VMO/MMO (§25.255(a): trimmed at
cruise speeds up to VMO/MMO) moved nose up and nose down by three seconds of the trim rate, within the trim limits
(§25.255(a)(1)), and held there: the elevator balances, and a balance that needs it past its stop fails (the
stabiliser is not retrimmed — the mistrim is the condition). Without a declared rate they are listed as not
evaluated.
"""

from __future__ import annotations

from certkit_rules.part25.support.balanced_runs import (
    BALANCED_CONDITIONS,
    BALANCED_REQUIRES,
    BALANCED_RUN_CRITERIA,
    SURFACES,
    balanced_runs,
)

from certkit.engine.evidence.loads import run_envelope_evidence
from certkit.engine.registry import Loads, SimulationRule, rule


@rule
class BalancedManeuver(SimulationRule):
    id = "25.331(b)"
    produces = tuple(Loads(s) for s in SURFACES)
    cost = 2
    run_with = "discrete-gust"  # §25.427(b) splits these balanced states' tail loads: one process computes them once
    symbol = "balanced-maneuver"
    title = "Maneuvering balanced conditions on the V–n envelope"
    amendment = "25-141"
    requirement = """
        Assuming the airplane to be in equilibrium with zero pitching acceleration, the manoeuvring conditions
        on the manoeuvring envelope of §25.333(b) must be investigated; flaps extended, the airplane is
        designed for manoeuvring to a positive limit load factor of 2.0 at the design flap speeds (§25.345(a)).
        The structure carries the limit loads (§25.305(a)) and 1.5 × them (ultimate, §25.303, §25.305(b)).
    """
    margin = """
        Per condition and surface (wing, horizontal tail): the smallest of (allowable limit load − |limit load|)
        and (allowable ultimate load − 1.5 × |limit load|) over the declared stations and quantities (shear,
        bending, torsion), the loads of the balanced state; without a declared structural capability the
        condition reports its loads and is not evaluated.
    """
    references = ("25.333", "25.335", "25.337", "25.345", "25.303", "25.305")
    requires = BALANCED_REQUIRES
    criteria = dict(BALANCED_RUN_CRITERIA)
    conditions = BALANCED_CONDITIONS
    limitations = (
        "Rigid airplane, quasi-steady linear strip aerodynamics (lift linear up to C_N,max); the §25.333(b) "
        "figure is unverified, its points C, G, I are not assumed (the VC point on the n₊ line is "
        "evaluated); flaps extended the flap lift is the configuration's increment (declared, or Raymer's "
        "estimate) spread with the linear lattice's flap distribution (a slotted flap's chordwise extension and "
        "its lift's X position are those of a plain flap), and VF is the larger of the placard VFE and the "
        "§25.335(e)(3) minima; the wing is evaluated in each fuel state of the §25.343 range at the condition's weight "
        "and CG (tanks used in the reverse of the declared filling order), the critical one named in the "
        "finding. Out of trim (§25.331(a)(2)): the §25.255(a)(1) mistrim only (not the (a)(2) autopilot "
        "mistrim), at the points at VC and VD; points A and H lie at speeds below the cruise speeds §25.255 trims at."
    )
    implementation = "partial"
    unevaluated = (
        ("25.333(b)", "points C, G and I of the manoeuvring envelope are not evaluated (the figure is unverified)"),
        (
            "25.345(a)",
            "the §25.345(a)(2) 25 ft/s head-on and vertical flap gusts are not evaluated",
        ),
        (
            "25.333",
            "C_N,max does not vary with Mach and no buffet-onset boundary limits the manoeuvring envelope at altitude",
        ),
    )

    def simulate(self, ctx, conditions, crit):
        return balanced_runs(ctx, conditions, crit)

    def evidence(self, ctx, findings, crit):
        return run_envelope_evidence(self.run, ctx, crit.ultimate_factor, SURFACES, "balanced manoeuvres")
