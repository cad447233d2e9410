"""The study store: one SQLite file (WAL journal), one row per case, written by one process.

The coordinating process is the only writer (an exclusive lock on ``<store>.lock`` for the length of a run)
and commits each finished case in its own transaction, so that a coordinator killed at any moment leaves
every committed case in place and the uncommitted ones pending. A result is written only over a pending row
(``WHERE status = 'pending'``): a case is never recorded twice. Readers (status, export, the analysis) may
read while a run writes.

A record is kept as canonical JSON (sorted keys) without its ``timings``, which are kept apart: the records
of two runs of the same study compare byte for byte whatever the executor or the machine's load.
"""

from __future__ import annotations

import json
import math
import os
import sqlite3
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any

from certkit.errors import UserError
from certkit.study.plan import Case, CaseContext, Plan
from certkit.study.spec import Study
from certkit.study.worker import CaseResult

if TYPE_CHECKING:
    import pandas as pd

SCHEMA_VERSION = "1"

_SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (name TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS cases (
    key TEXT PRIMARY KEY,
    seq INTEGER NOT NULL,           -- order of the plan (design rows) or of insertion (extra rows)
    block TEXT NOT NULL,
    role TEXT NOT NULL,
    idx INTEGER NOT NULL,           -- position in its block
    origin TEXT NOT NULL CHECK (origin IN ('design', 'extra')),
    in_plan INTEGER NOT NULL,       -- part of the current study (design rows: in its plan; extra rows: same context)
    context TEXT NOT NULL,          -- CaseContext.digest
    variables TEXT NOT NULL,        -- JSON {path: SI value}
    status TEXT NOT NULL CHECK (status IN ('pending', 'ok', 'failed')),
    error TEXT,
    wall_s REAL,
    worker TEXT,
    record TEXT,                    -- canonical JSON of the record without "timings"
    timings TEXT,                   -- JSON of the record's "timings"
    finished_at REAL
);
CREATE INDEX IF NOT EXISTS cases_status ON cases (status, in_plan);
"""


class Store:
    def __init__(self, path: Path, connection: sqlite3.Connection):
        self.path = path
        self._db = connection

    # -- opening -------------------------------------------------------------------------------------------

    @classmethod
    def open(cls, path: str | Path, create: bool = False) -> "Store":
        path = Path(path)
        if not create and not path.is_file():
            raise UserError(f"{path}: no study store here (run `certkit study run` first)")
        path.parent.mkdir(parents=True, exist_ok=True)
        try:
            db = sqlite3.connect(path, isolation_level=None, timeout=30.0)
            db.execute("PRAGMA journal_mode=WAL")
            db.execute("PRAGMA synchronous=FULL")
            if create:
                db.executescript(_SCHEMA)
                db.execute("INSERT OR IGNORE INTO meta VALUES ('schema', ?)", (SCHEMA_VERSION,))
            version = db.execute("SELECT value FROM meta WHERE name = 'schema'").fetchone()
            damage = [row[0] for row in db.execute("PRAGMA quick_check(3)")]
        except sqlite3.DatabaseError as exc:
            raise UserError(
                f"{path}: not a certkit study store, or a damaged one (SQLite: {exc}); restore it from a "
                "copy, or delete it and run the study again"
            ) from None
        if damage != ["ok"]:
            raise UserError(
                f"{path}: damaged study store (SQLite: {'; '.join(damage)}); restore it from a copy, or "
                "delete it and run the study again"
            )
        if version is None or version[0] != SCHEMA_VERSION:
            raise UserError(
                f"{path}: study store of another format ({version and version[0]}; expected {SCHEMA_VERSION})"
            )
        return cls(path, db)

    def close(self) -> None:
        self._db.close()

    def __enter__(self) -> "Store":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    @contextmanager
    def writer(self) -> Iterator[Store]:
        """Exclusive right to write, for one run: a second coordinator on the same store is refused. The lock
        (flock) dies with its process, so a killed coordinator never leaves the store locked."""
        import fcntl  # deferred: fcntl is POSIX-only: a store is still read where it is absent

        lock_path = self.path.with_name(self.path.name + ".lock")
        fd = os.open(lock_path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                raise UserError(f"{self.path}: another `certkit study run` is writing this store") from None
            yield self
        finally:
            os.close(fd)

    @contextmanager
    def _transaction(self) -> Iterator[sqlite3.Connection]:
        self._db.execute("BEGIN IMMEDIATE")
        try:
            yield self._db
        except BaseException:
            self._db.execute("ROLLBACK")
            raise
        self._db.execute("COMMIT")

    # -- writing (the coordinator) ---------------------------------------------------------------------------

    def sync_plan(self, study: Study, context: CaseContext, plan: Plan) -> None:
        """Record the study and its plan: new cases become pending, cases already present keep their result
        (and take the block of the current plan); design rows outside the plan, and extra rows of another
        context, leave the study (they stay in the file)."""
        with self._transaction() as db:
            db.execute("INSERT OR REPLACE INTO meta VALUES ('study', ?)", (study.model_dump_json(),))
            db.execute("INSERT OR REPLACE INTO meta VALUES ('context', ?)", (context.digest,))
            db.execute("INSERT OR REPLACE INTO meta VALUES ('evaluator', ?)", (context.evaluator,))
            db.execute("UPDATE cases SET in_plan = 0 WHERE origin = 'design'")
            db.executemany(
                "INSERT INTO cases (key, seq, block, role, idx, origin, in_plan, context, variables, status) "
                "VALUES (?, ?, ?, ?, ?, 'design', 1, ?, ?, 'pending') ON CONFLICT (key) DO UPDATE SET "
                "seq = excluded.seq, block = excluded.block, role = excluded.role, idx = excluded.idx, "
                "origin = 'design', in_plan = 1",
                [
                    (c.key, seq, c.block, c.role, c.index, context.digest, json.dumps(c.values))
                    for seq, c in enumerate(plan.cases)
                ],
            )
            db.execute("UPDATE cases SET in_plan = (context = ?) WHERE origin = 'extra'", (context.digest,))

    def add_cases(self, context: CaseContext, cases: list[Case]) -> None:
        """Cases outside the study's designs (e.g. a check sample); a case of the current study keeps its row,
        one that had left the study (same context) comes back as an extra row, with its result."""
        with self._transaction() as db:
            start = db.execute("SELECT COALESCE(MAX(seq), -1) + 1 FROM cases WHERE origin = 'extra'").fetchone()[0]
            db.executemany(
                "INSERT INTO cases (key, seq, block, role, idx, origin, in_plan, context, variables, status) "
                "VALUES (?, ?, ?, ?, ?, 'extra', 1, ?, ?, 'pending') ON CONFLICT (key) DO UPDATE SET "
                "origin = 'extra', in_plan = 1, seq = excluded.seq, block = excluded.block, role = excluded.role, "
                "idx = excluded.idx WHERE in_plan = 0",
                [
                    (c.key, start + i, c.block, c.role, c.index, context.digest, json.dumps(c.values))
                    for i, c in enumerate(cases)
                ],
            )

    def commit(self, result: CaseResult, finished_at: float) -> bool:
        """Write one finished case (its own transaction); False if it was no longer pending."""
        with self._transaction() as db:
            cursor = db.execute(
                "UPDATE cases SET status = ?, error = ?, wall_s = ?, worker = ?, record = ?, timings = ?, "
                "finished_at = ? WHERE key = ? AND status = 'pending'",
                (
                    result.status,
                    result.error,
                    result.wall_s,
                    result.worker,
                    result.record,
                    result.timings,
                    finished_at,
                    result.key,
                ),
            )
            return bool(cursor.rowcount == 1)

    def reset_failed(self) -> int:
        """Failed cases of the current study back to pending (an explicit retry)."""
        with self._transaction() as db:
            return int(
                db.execute(
                    "UPDATE cases SET status = 'pending', error = NULL, record = NULL, timings = NULL "
                    "WHERE status = 'failed' AND in_plan = 1"
                ).rowcount
            )

    # -- reading ---------------------------------------------------------------------------------------------

    def meta(self, name: str) -> str | None:
        row = self._db.execute("SELECT value FROM meta WHERE name = ?", (name,)).fetchone()
        return row[0] if row else None

    def study(self) -> Study:
        """The validated study definition of the last run (SI values; the aircraft as an absolute path)."""
        text = self.meta("study")
        if text is None:
            raise UserError(f"{self.path}: no study recorded yet")
        return Study.model_validate_json(text)

    def pending(self, keys: list[str] | None = None) -> list[Case]:
        """Cases of the current study (or of ``keys``) still without a result, in plan order."""
        rows = self._db.execute(
            "SELECT key, block, role, idx, variables FROM cases WHERE status = 'pending' AND in_plan = 1 "
            "ORDER BY origin = 'extra', seq"
        ).fetchall()
        if keys is not None:
            wanted = set(keys)
            rows = [r for r in rows if r[0] in wanted]
        return [Case(key, block, role, idx, json.loads(values)) for key, block, role, idx, values in rows]

    def counts(self) -> list[tuple[str, str, str, int]]:
        """(block, role, status, cases) of the current study, blocks in plan order."""
        return self._db.execute(
            "SELECT block, role, status, COUNT(*) FROM cases WHERE in_plan = 1 GROUP BY block, role, status "
            "ORDER BY MIN(origin = 'extra'), MIN(seq), status"
        ).fetchall()

    def stale(self) -> int:
        """Rows kept in the file but outside the current study (another plan, aircraft, version or responses)."""
        return int(self._db.execute("SELECT COUNT(*) FROM cases WHERE in_plan = 0").fetchone()[0])

    def rows(self, keys: list[str] | None = None, include_stale: bool = False) -> list[dict[str, Any]]:
        """Rows as dicts (variables and record parsed), in plan order."""
        where = "" if include_stale else "WHERE in_plan = 1"
        cursor = self._db.execute(
            "SELECT key, block, role, status, error, wall_s, worker, variables, record, timings, finished_at "
            f"FROM cases {where} ORDER BY origin = 'extra', seq"
        )
        names = [d[0] for d in cursor.description]
        out = []
        wanted = set(keys) if keys is not None else None
        for values in cursor:
            row = dict(zip(names, values))
            if wanted is not None and row["key"] not in wanted:
                continue
            row["variables"] = json.loads(row["variables"])
            row["record"] = json.loads(row["record"]) if row["record"] else None
            row["timings"] = json.loads(row["timings"]) if row["timings"] else None
            out.append(row)
        return out

    def raw_records(self) -> dict[str, str | None]:
        """key → the record's stored JSON text (for byte-for-byte comparisons)."""
        return dict(self._db.execute("SELECT key, record FROM cases WHERE in_plan = 1"))

    def frame(self, include_stale: bool = False) -> pd.DataFrame:
        """One row per case: key, block, role, status, error, wall_s, worker, ``var:<path>`` (SI) for each
        variable, ``resp:<name>`` for each response recorded (NaN when absent or not computed)."""
        import pandas as pd  # deferred: pandas (0.2 s) only for a frame; `study run` needs none

        rows = self.rows(include_stale=include_stale)
        try:
            paths = self.study().variable_paths()
        except UserError:
            paths = []
        for row in rows:
            paths += [p for p in row["variables"] if p not in paths]
        responses = sorted({name for row in rows if row["record"] for name in row["record"].get("responses", {})})
        table = []
        for row in rows:
            out = {k: row[k] for k in ("key", "block", "role", "status", "error", "wall_s", "worker")}
            out.update({f"var:{p}": row["variables"].get(p, math.nan) for p in paths})
            found = (row["record"] or {}).get("responses", {})
            out.update({f"resp:{n}": math.nan if found.get(n) is None else float(found[n]) for n in responses})
            table.append(out)
        columns = (
            ["key", "block", "role", "status", "error", "wall_s", "worker"]
            + [f"var:{p}" for p in paths]
            + [f"resp:{n}" for n in responses]
        )
        return pd.DataFrame(table, columns=columns)


def export(store: Store, out: Path, fmt: str) -> Path:
    """Write the study's frame as CSV or Parquet (pyarrow)."""
    frame = store.frame()
    if fmt == "csv":
        frame.to_csv(out, index=False)
    elif fmt == "parquet":
        try:
            frame.to_parquet(out, index=False, engine="pyarrow")
        except ImportError:
            raise UserError("Parquet export needs pyarrow: pip install pyarrow (or export --format csv)") from None
    else:
        raise UserError(f"unknown export format {fmt!r} (csv or parquet)")
    return out
