"""The folder of vortex-lattice solutions kept between checks (:mod:`certkit.models.aero.lattice_store`): an entry is
found only by inputs that are all the solution reads, gives back exactly what solving gives, and a damaged entry or
an unwritable folder costs time, never a run."""

from __future__ import annotations

import os

import numpy as np

from certkit.aircraft.model import Aircraft
from certkit.models.aero import lattice_store
from certkit.models.aero.airplane import lattice_derivatives
from certkit.models.aero.lattice_store import KEEP, LATTICE_INPUTS, LatticeStore, entry_key


def _tail_scaled(aircraft, factor):
    """The aircraft with its horizontal tail's area × ``factor`` at the same aspect ratio."""
    tail = aircraft.geometry.horizontal_tail
    bigger = tail.model_copy(update={"area": tail.area * factor})
    return aircraft.model_copy(update={"geometry": aircraft.geometry.model_copy(update={"horizontal_tail": bigger})})


def _sections_read(aircraft, monkeypatch) -> set[str]:
    """The aircraft's attributes (its file's sections) that solving its lattice reads."""
    seen: set[str] = set()
    original = Aircraft.__getattribute__

    def recording(self, name):
        if self is aircraft:
            seen.add(name)
        return original(self, name)

    monkeypatch.setattr(Aircraft, "__getattribute__", recording)
    lattice_derivatives(aircraft)
    monkeypatch.setattr(Aircraft, "__getattribute__", original)
    return seen


def test_the_key_holds_every_section_the_lattice_reads(baseline, monkeypatch):
    """Whatever the solution reads of the aircraft is in its key (a section read but not keyed would let an edit of
    it find the old solution): the baseline, and a wing without flaps (another path through the lattice's set-up).
    The recording sees reads: at least the geometry."""
    ac = baseline.model
    no_flaps = ac.model_copy(
        update={
            "geometry": ac.geometry.model_copy(update={"wing": ac.geometry.wing.model_copy(update={"flaps": None})})
        }
    )
    for aircraft in (ac, no_flaps):
        read = _sections_read(aircraft, monkeypatch)
        assert "geometry" in read
        assert read <= set(LATTICE_INPUTS), sorted(read - set(LATTICE_INPUTS))


def test_a_stored_solution_is_the_solved_one_and_another_geometry_is_solved_afresh(baseline, tmp_path):
    """Solved once and stored; a second store on the folder loads it: the derivative tables, neutral points, span
    efficiencies and the lattice's unit solutions exactly as solved. The tail 20 % larger is another entry and its own
    solution (a stronger pitch stability, Cm_alpha more negative); a change of a section the lattice does not read
    (the mass data) is the same entry."""
    ac = baseline.model
    solved = lattice_derivatives(ac)
    LatticeStore(tmp_path).derivatives(ac)
    assert len(list(tmp_path.glob("*.pickle"))) == 1
    table, xnp, e, vl = LatticeStore(tmp_path).derivatives(ac)
    assert (xnp, e) == (solved[1], solved[2])
    for name, values in solved[0].items():
        if isinstance(values, list):
            assert table[name] == values, name
    np.testing.assert_array_equal(vl.unit_circulation, solved[3].unit_circulation)
    np.testing.assert_array_equal(vl.force_tensor, solved[3].force_tensor)

    bigger = _tail_scaled(ac, 1.2)
    assert entry_key(bigger) != entry_key(ac)
    own = LatticeStore(tmp_path).derivatives(bigger)
    assert own[0]["Cm_alpha"][0] < table["Cm_alpha"][0] - 0.05 * abs(table["Cm_alpha"][0])
    assert own[0]["Cm_alpha"] == lattice_derivatives(bigger)[0]["Cm_alpha"]
    assert len(list(tmp_path.glob("*.pickle"))) == 2

    heavier = ac.model_copy(update={"mass": ac.mass.model_copy(update={"MTOW": ac.mass.MTOW * 1.1})})
    assert entry_key(heavier) == entry_key(ac)
    assert entry_key(ac, machs=[0.2, 0.5]) != entry_key(ac)


def test_a_damaged_entry_is_solved_again_and_an_unwritable_folder_only_costs_time(baseline, tmp_path):
    ac = baseline.model
    LatticeStore(tmp_path).derivatives(ac)
    (entry,) = tmp_path.glob("*.pickle")
    with open(entry, "r+b") as f:
        f.truncate(100)  # as a process killed mid-write would leave it (the store writes whole files only)
    table = LatticeStore(tmp_path).derivatives(ac)[0]
    assert table["CL_alpha"] == lattice_derivatives(ac)[0]["CL_alpha"]
    assert entry.stat().st_size > 1_000_000  # written again, whole
    blocked = tmp_path / "a file"
    blocked.write_text("where the folder would be")
    assert LatticeStore(blocked / "lattices").derivatives(ac)[0]["CL_alpha"] == table["CL_alpha"]
    assert not list(tmp_path.glob("*.tmp"))


def test_the_newest_entries_are_kept(baseline, tmp_path):
    """The folder keeps the :data:`KEEP` most recently used entries: older ones go when a new one is written; a
    read makes an entry recent."""
    for i in range(KEEP + 2):
        old = tmp_path / f"{i:064x}.pickle"
        old.write_bytes(b"x")
        os.utime(old, ns=(10**18 + i * 10**9, 10**18 + i * 10**9))
    LatticeStore(tmp_path).derivatives(baseline.model)
    kept = sorted(p.name for p in tmp_path.glob("*.pickle"))
    assert len(kept) == KEEP
    assert f"{entry_key(baseline.model)}.pickle" in kept
    assert f"{0:064x}.pickle" not in kept and f"{KEEP + 1:064x}.pickle" in kept


def test_the_key_follows_certkit_source(baseline, monkeypatch):
    """Another certkit (a module's text changed) never finds this one's solution."""
    key = entry_key(baseline.model)
    monkeypatch.setattr(lattice_store, "source_digest", lambda: "another certkit")
    assert entry_key(baseline.model) != key


def test_rules_on_a_stored_lattice_give_the_same_results(baseline, tmp_path):
    """A check's rules on the lattice loaded from the folder write the same results as on a lattice solved in the
    run: §25.173(a) (trims) and §25.331(c)(1)'s checked manoeuvre (the strip loads spread the lattice's unit
    solutions)."""
    from certkit.engine.registry import discover
    from certkit.engine.scheduler import run

    rules = [r for r in discover() if r.id in ("25.173(a)", "25.331(c)(1)")]
    solved = run(baseline, rules, jobs=1)
    store = LatticeStore(tmp_path)
    run(baseline, rules, jobs=1, lattice_store=store)
    assert len(list(tmp_path.glob("*.pickle"))) == 1
    loaded = run(baseline, rules, jobs=1, lattice_store=store)
    assert [r.to_json() for r in loaded.rules] == [r.to_json() for r in solved.rules]
    assert all(r.findings for r in loaded.rules)


def test_the_key_follows_the_blas_thread_settings(baseline, monkeypatch):
    """A lattice solved with a threaded BLAS (other last bits: its LU sums in another order) is another entry than one
    solved with one thread, as certkit's commands run."""
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "1")
    one = entry_key(baseline.model)
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "2")
    assert entry_key(baseline.model) != one
