"""A changed kernel source never runs against machine code compiled from the old one.

numba keys a cached kernel on its own file only; certkit's equations of motion inline the aerodynamic coefficients of
another module, so after a change of that module (a derivative table's row layout) the old machine code read the new
tables one row off — every straight flight then needed full aileron. certkit keeps a digest of its kernel sources
beside the cache and removes its cached kernels when it changes (:func:`certkit.models.compiled.refresh_stale_kernels`).
"""

import shutil
from pathlib import Path

import numba

import certkit
from certkit.models.compiled import DIGEST_FILE, KERNEL_MODULES, kernel_cache_dirs, refresh_stale_kernels

PACKAGE = Path(certkit.__file__).parent


def test_the_list_of_kernel_modules_is_the_packages():
    """Every certkit module with a disk-cached kernel (``cache=True``) is listed, and nothing else."""
    cached = {str(p.relative_to(PACKAGE)) for p in PACKAGE.rglob("*.py") if "cache=True" in p.read_text()}
    assert cached == set(KERNEL_MODULES)


def _copy(tmp_path):
    package = tmp_path / "pkg"
    for module in KERNEL_MODULES:
        (package / module).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(PACKAGE / module, package / module)
    return package


def test_a_changed_source_removes_the_cached_kernels_once(tmp_path, monkeypatch):
    """With the cache in a directory of its own (NUMBA_CACHE_DIR): cached kernel files of the listed modules are
    removed when a kernel source changes, kept while none does, and another program's files are never touched."""
    monkeypatch.setattr(numba.config, "CACHE_DIR", str(tmp_path / "cache"))
    package = _copy(tmp_path)
    dirs = kernel_cache_dirs(package)
    assert sum(len(stems) for stems in dirs.values()) == len(KERNEL_MODULES)
    (directory, stems) = next((d, s) for d, s in dirs.items() if "kernel" in s)

    def fake_cache():
        directory.mkdir(parents=True, exist_ok=True)
        ours = [directory / "kernel.derivatives-100.py311.nbi", directory / "kernel.derivatives-100.py311.1.nbc"]
        theirs = directory / "othermodule.f-3.py311.nbi"
        for f in (*ours, theirs):
            f.write_bytes(b"x")
        return ours, theirs

    refresh_stale_kernels(package)  # the first run writes the digest
    assert (directory / DIGEST_FILE).exists()
    ours, theirs = fake_cache()
    assert refresh_stale_kernels(package) == []  # unchanged sources: the cache is kept
    assert all(f.exists() for f in ours)
    source = package / "models/aero/derivative_kernel.py"
    source.write_text(source.read_text() + "\n# a changed table layout\n")
    removed = refresh_stale_kernels(package)
    assert set(ours) <= set(removed) and not any(f.exists() for f in ours)
    assert theirs.exists()
    fake_cache()
    assert refresh_stale_kernels(package) == []  # once per change
