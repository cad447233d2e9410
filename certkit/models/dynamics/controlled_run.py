"""The compiled closed-loop run (:func:`certkit.models.dynamics.pilot_kernel.integrate_controlled`) from Python:
which runs it serves, and the laws' blocks.

A controller or stop criterion that the kernel can step offers ``kernel_block()``: a :class:`KernelBlock` with its
constants, per-row parameters and state (the layouts are those of the kernel's law functions), or None when it
cannot (e.g. already stepped by a run). :func:`controlled_blocks` accepts a run whose laws come in the kernel's order
(pitch, lateral, failure; each at most once) with at most one stop criterion, on a model whose thrust is computed in
compiled code; :func:`run_controlled` runs it and writes every block's final state back
into its object, and the engines' state into the model, as the Python loop leaves them.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from certkit.models.compiled import kernel_array
from certkit.models.dynamics import pilot_kernel
from certkit.models.dynamics.eom import AircraftModel

#: the laws' order in a compiled run
ROLES = ("pitch", "lateral", "failure")


@dataclass
class KernelBlock:
    """One law or stop criterion of a compiled run: ``role`` (:data:`ROLES` or "stop"), ``kind`` (the kernel's
    constant), ``consts`` (C,), ``params`` (n, P), ``state`` (n, S) stepped in place, ``restore(state)`` writing the
    final state back into ``source`` (the Python object); ``columns`` the control columns (lateral: aileron, rudder,
    steering or −1), ``mask`` the failed engines (failure), ``waits_for`` the failure a law or criterion reads."""

    role: str
    kind: int
    consts: np.ndarray
    params: np.ndarray
    state: np.ndarray
    restore: Callable[[np.ndarray], None]
    source: Any = None
    columns: tuple[int, ...] = (-1, -1, -1)
    mask: np.ndarray | None = None
    waits_for: Any = field(default=None)


def columns(n: int, *values) -> np.ndarray:
    """Per-row values (scalars or (n,) arrays) as the columns of an (n, k) float array."""
    return np.column_stack([np.broadcast_to(np.asarray(v, dtype=float), (n,)) for v in values])


def controlled_blocks(
    model: AircraftModel, controllers: Sequence[Any], stop: Sequence[Any]
) -> list[KernelBlock] | None:
    """The blocks of a run the kernel can step, in order (laws, then the stop criterion), or None."""
    if not model.thrust_compiled or len(stop) > 1:
        return None
    blocks = []
    for item in (*controllers, *stop):
        make = getattr(item, "kernel_block", None)
        block = make() if make is not None and _own_block(type(item)) else None
        if block is None:
            return None
        blocks.append(block)
    laws = [b.role for b in blocks[: len(controllers)]]
    if any(r not in ROLES for r in laws) or laws != sorted(set(laws), key=ROLES.index):
        return None
    if any(getattr(b.source, "model", model) is not model for b in blocks):
        return None  # a law of another model (the Python loop would step that model's engines)
    failure = next((b.source for b in blocks if b.role == "failure"), None)
    if any(b.waits_for is not None and b.waits_for is not failure for b in blocks):
        return None
    if stop and blocks[-1].role != "stop":
        return None
    return blocks


def _defining(cls: type, name: str) -> type | None:
    return next((c for c in cls.__mro__ if name in vars(c)), None)


def _own_block(cls: type) -> bool:
    """Is the class's block the one of its own law (not inherited past a subclass that changes the law)?"""
    law = _defining(cls, "update") or _defining(cls, "__call__")
    return law is not None and _defining(cls, "kernel_block") is law


def _empty(n: int) -> np.ndarray:
    return np.zeros((n, 1))


def run_controlled(
    model: AircraftModel,
    x13: np.ndarray,
    U_all: np.ndarray,
    dt: float,
    nsteps: int,
    record_every: int,
    blocks: list[KernelBlock],
    out_rec: np.ndarray,
    x_rec: np.ndarray,
    u_rec: np.ndarray,
) -> tuple[int, np.ndarray]:
    """Run the blocks' laws over the batch from ``x13`` (advanced in place), ``U_all`` every step's controls before
    the laws ((1, n, m): the same at every step); the number of records and the step each row stopped at (−1:
    none)."""
    n = x13.shape[0]
    by_role = {b.role: b for b in blocks}
    pitch, lateral, failure, stop = (by_role.get(r) for r in (*ROLES, "stop"))
    operative = kernel_array(model.operative, np.bool_).copy()
    fraction = kernel_array(model.failed_thrust_fraction).copy()
    stop_step = np.full(n, -1, dtype=np.int64)

    def parts(block: KernelBlock | None) -> tuple:
        if block is None:
            return 0, np.zeros(1), _empty(n), _empty(n)
        params, state = (kernel_array(a) if a.shape[0] == n else _empty(n) for a in (block.params, block.state))
        return block.kind, kernel_array(block.consts), params, state

    p_kind, p_c, p_p, p_s = parts(pitch)
    l_kind, l_c, l_p, l_s = parts(lateral)
    s_kind, s_c, s_p, s_s = parts(stop)
    _, f_c, f_p, f_s = parts(failure)  # read by the kernel only when there is a failure
    f_mask = np.zeros(operative.shape[1], dtype=np.bool_) if failure is None else kernel_array(failure.mask, np.bool_)
    irec = pilot_kernel.integrate_controlled(
        x13,
        kernel_array(U_all),
        float(dt),
        int(nsteps),
        int(record_every),
        model._turbofan,
        model.throttle_slice.start,
        operative,
        fraction,
        model._windmill,
        p_kind,
        p_c,
        p_p,
        p_s,
        l_kind,
        np.array(lateral.columns if lateral is not None else (-1, -1, -1), dtype=np.int64),
        l_c,
        l_p,
        l_s,
        failure is not None,
        f_mask,
        f_c,
        f_p,
        f_s,
        s_kind,
        s_c,
        s_p,
        s_s,
        out_rec,
        x_rec,
        u_rec,
        stop_step,
        np.empty((n, 8)),
        *model._kernel_args,
    )
    for block, state in ((pitch, p_s), (lateral, l_s), (failure, f_s), (stop, s_s)):
        if block is not None:
            block.restore(state)
    if failure is not None and f_s[:, 0].any():  # the engines as EngineFailure leaves them
        model.set_operative(operative)
        if np.isfinite(f_c[0]):
            model.failed_thrust_fraction = fraction
    return int(irec), stop_step


__all__ = ["ROLES", "KernelBlock", "columns", "controlled_blocks", "run_controlled"]
