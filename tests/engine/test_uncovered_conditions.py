"""The scheduler's check that every scheduled condition got a finding (itself or refined): the indexed search against
the definition applied to every pair (``Condition.refines``), on random schedules and findings."""

import random

from certkit.engine.results import Condition, Finding
from certkit.engine.scheduler import _uncovered


def _random_condition(rng, scheduled: bool) -> Condition:
    c = Condition(
        loading=rng.choice(["fwd", "aft", None]) if scheduled else rng.choice(["fwd", "aft"]),
        mass=rng.choice([1.0, 2.0]),
        configuration=rng.choice(["clean", "landing"]),
        altitude=rng.choice([0.0, 1000.0, None]) if scheduled else rng.choice([0.0, 1000.0]),
    )
    names = rng.sample(["point", "trim", "direction"], rng.randint(0, 3))
    for k in names:
        c = c.with_(**{k: rng.choice(["a", "b", 1.0, 1])})
    if not scheduled and rng.random() < 0.5:
        c = c.with_(speed=rng.choice([100.0, 120.0]), speed_kind="EAS")
    return c


def test_indexed_search_matches_the_definition():
    rng = random.Random(7)
    for _ in range(200):
        scheduled = [_random_condition(rng, True) for _ in range(rng.randint(1, 30))]
        found = [_random_condition(rng, False) for _ in range(rng.randint(0, 40))]
        # some findings are the scheduled conditions refined (a speed set, an extra item added)
        found += [c.with_(speed=90.0, speed_kind="CAS", detail="x") for c in rng.sample(scheduled, len(scheduled) // 3)]
        findings = [Finding.not_evaluated(c, "check", "test") for c in found]
        expected = [c for c in scheduled if not any(f.condition == c or f.condition.refines(c) for f in findings)]
        assert _uncovered(scheduled, findings) == expected


def test_expanded_conditions_are_those_of_the_constructor(ctx):
    """The condition space's points (built field by field, without the dataclass ``__init__``) equal, hash and order
    their fields as conditions made by ``Condition(...)``; ``with_`` and ``without`` on them too."""
    import dataclasses

    from certkit.engine.conditions import CgCorners, ConditionSpace, EnvelopeAltitudes

    space = ConditionSpace(
        loading=CgCorners(), configurations=("clean",), altitudes=EnvelopeAltitudes(), extra=(("gust", ("up", "down")),)
    )
    points = space.expand(ctx.aircraft)
    assert len(points) > 8
    names = [f.name for f in dataclasses.fields(Condition)]
    for c in points:
        made = Condition(**{n: getattr(c, n) for n in names})
        assert c == made and hash(c) == hash(made) and list(vars(c)) == names == list(vars(made))
        assert c.with_(gust="down").without("gust") == made.with_(gust="down").without("gust")
