"""certkit's processes do not execute numpy.f2py nor import dask at start-up (:mod:`certkit.lean_imports`), and both
still work when asked for: f2py's functions on first use, dask by a later import."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from ..conftest import ROOT

PROBE = """
import json, sys
import certkit.units, scipy.linalg, numpy
before = {"f2py_executed": "numpy.f2py.crackfortran" in sys.modules, "dask": "dask" in sys.modules,
          "numpy_f2py_bound": "numpy.f2py" in sys.modules}
import numpy.f2py
usable = callable(numpy.f2py.run_main)
after = "numpy.f2py.crackfortran" in sys.modules
try:
    import dask
    dask_ok = hasattr(dask, "compute")
except ImportError:
    dask_ok = None
print(json.dumps({**before, "f2py_usable": usable, "f2py_executed_after_use": after, "dask_after": dask_ok}))
"""


def _probe() -> dict:
    out = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, cwd=ROOT, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_start_up_skips_f2py_and_dask_and_both_work_when_used():
    got = _probe()
    assert got["numpy_f2py_bound"] is True  # scipy's `from numpy import *` bound it…
    assert got["f2py_executed"] is False  # …without executing it
    assert got["dask"] is False
    assert got["f2py_usable"] is True and got["f2py_executed_after_use"] is True
    if got["dask_after"] is None:
        pytest.skip("dask is not installed here (the import after start-up is not tested)")
    assert got["dask_after"] is True


def test_pint_sees_no_dask_and_dask_imported_first_is_kept():
    code = "import dask, certkit.units, pint.compat as c, sys; print(c.HAS_DASK, 'dask' in sys.modules)"
    try:
        import dask  # noqa: F401
    except ImportError:
        pytest.skip("dask is not installed here")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True)
    assert out.stdout.split() == ["True", "True"]  # a process that imported dask first keeps pint's dask support
    out = subprocess.run(
        [sys.executable, "-c", "import certkit.units, pint.compat as c; print(c.HAS_DASK)"],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=True,
    )
    assert out.stdout.split() == ["False"]


def test_numba_sets_up_its_typing_without_cffi_and_cffi_still_imports():
    code = (
        "import sys, certkit.models.compiled\n"
        "from numba.core.registry import cpu_target\n"
        "cpu_target.target_context.refresh()\n"
        "from numba.core.typing import cffi_utils\n"
        "print('cffi' in sys.modules, cffi_utils.SUPPORTED)\n"
        "try:\n"
        "    import cffi\n"
        "    print(hasattr(cffi, 'FFI'))\n"
        "except ImportError:\n"
        "    print('absent')\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True)
    words = out.stdout.split()
    assert words[:2] == ["False", "False"]  # numba's typing set up, cffi never imported, its support recorded absent
    if words[2] == "absent":
        pytest.skip("cffi is not installed here (the import afterwards is not tested)")
    assert words[2] == "True"
