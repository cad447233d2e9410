"""Errors meant for people: what, where, the value, the expectation.

A user mistake (a bad aircraft file, an unknown rule id, a bad option) raises :class:`UserError`
or :class:`InputError`; the CLI prints the message and exits with code 2, without a traceback.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Problem:
    """One problem of an input file, located by its dotted path and line."""

    path: str
    message: str
    value: object = None
    line: int | None = None
    file: str | None = None

    def __str__(self) -> str:
        where = self.path or "(top level)"
        loc = f"{self.file}:{self.line}: " if self.file and self.line else (f"line {self.line}: " if self.line else "")
        shown = "" if self.value is None else f" (got {_short(self.value)})"
        return f"{loc}{where}: {self.message}{shown}"


def _short(value: object, limit: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


class UserError(Exception):
    """A mistake the user can fix; its message is printed as is (exit code 2)."""


class InputError(UserError):
    """Every problem found in one input file, reported together."""

    def __init__(self, source: str, problems: list[Problem]):
        self.source = source
        self.problems = sorted(problems, key=lambda p: (p.line or 0, p.path))
        n = len(self.problems)
        head = f"{source}: {n} problem{'s' if n != 1 else ''} found"
        super().__init__("\n".join([head] + [f"  - {p}" for p in self.problems]))

    def __reduce__(
        self,
    ) -> tuple[type[InputError], tuple[str, list[Problem]]]:  # raised in a worker, re-raised in the parent
        return (InputError, (self.source, self.problems))


class InfeasibleDesign(UserError):
    """Design-variable values that make an impossible aircraft (taper above 1, a tail tip behind the fuselage end):
    a user error for one design (``certkit evaluate`` exits 2), a failed case with its reason in a study whose
    bounds reach such values."""
