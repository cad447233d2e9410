"""The report folder: its name, its checks before an evaluation, and writing it as one consistent set.

A set (``results.json`` and ``index.html``) is written into a new hidden sibling folder of the target
(``.certkit-<pid>-<random>.new``, files opened with ``O_EXCL | O_NOFOLLOW``, synced), which then takes the target's
place in one step: ``renameat2(RENAME_EXCHANGE)`` swaps the two folders atomically on Linux (see rename(2)), a
missing target is a plain rename. The previous set stays whole until the new one is complete, a reader sees the old
set or the new one, and no symlink inside the folder is ever followed (the old folder, links included, is removed
after the swap without following them). A target holding files certkit did not write (``--out .``) is not swapped:
its report files are replaced one by one (each a temporary file renamed into place, ``results.json`` first), which
keeps each file whole but not the pair; docs/usage.md says so.
"""

from __future__ import annotations

import ctypes
import errno
import hashlib
import os
import re
import shutil
import tempfile
import unicodedata
from collections.abc import Mapping, Sequence
from pathlib import Path

from certkit.errors import UserError
from certkit.interrupts import raise_if_requested

#: the files of one report set, in the order they are replaced when the folder cannot be swapped
REPORT_FILES = ("results.json", "index.html")
_TEMP = re.compile(r"^\.certkit-(\d+)-.+\.(new|old)$")
_AT_FDCWD = -100
_RENAME_EXCHANGE = 2  # <linux/fs.h>
_MAX_SLUG = 80


def report_folder_name(name: str) -> str:
    """A folder name for an aircraft name, distinct for distinct names: letters and digits of any script are kept
    (NFKC-normalised), other runs of characters become ``_``; when that changed the name (or left nothing, or a
    name such as ``.`` or ``..``), 8 hex digits of the name's SHA-256 are appended."""
    kept = re.sub(r"[^\w.-]+", "_", unicodedata.normalize("NFKC", name), flags=re.UNICODE).strip("._-")[:_MAX_SLUG]
    if kept and kept == name and kept not in (".", ".."):
        return kept
    digest = hashlib.sha256(name.encode("utf-8", "surrogatepass")).hexdigest()[:8]
    return f"{kept}-{digest}" if kept else f"aircraft-{digest}"


def prepare_output(out: str | Path) -> Path:
    """The folder the report will replace, checked before any evaluation: a symlink given as ``--out`` is followed
    (the user named it) but must lead somewhere; the path must be a folder or not exist; its parent is created and
    must let certkit create the new set beside it. Raises :class:`UserError` naming the path and the reason."""
    given = Path(out)
    try:
        return _checked_target(given)
    except OSError as exc:
        raise UserError(f"--out {str(given)!r}: cannot write the report there ({exc.strerror or exc})") from None


def _checked_target(given: Path) -> Path:
    for part in given.parts:
        if len(part.encode("utf-8", "surrogatepass")) > 255:  # NAME_MAX of Linux, macOS and Windows file systems
            raise OSError(errno.ENAMETOOLONG, os.strerror(errno.ENAMETOOLONG))
    target = Path(os.path.realpath(given) if given.is_symlink() else os.path.abspath(given))
    if given.is_symlink() and not target.exists():
        raise UserError(f"--out {str(given)!r}: a symbolic link to {str(target)!r}, which does not exist")
    if target.exists() and not target.is_dir():
        raise UserError(f"--out {str(given)!r}: exists and is not a folder")
    _refuse_foreign_entries(given, target)
    for folder in reversed(target.parents):
        if folder.exists() and not folder.is_dir():
            raise UserError(f"--out {str(given)!r}: {str(folder)!r} is a file, not a folder")
    target.parent.mkdir(parents=True, exist_ok=True)
    probe = tempfile.mkdtemp(prefix=f".certkit-{os.getpid()}-", suffix=".new", dir=target.parent)
    os.rmdir(probe)
    if len(target.name.encode("utf-8", "surrogatepass")) > os.pathconf(target.parent, "PC_NAME_MAX"):
        raise OSError(errno.ENAMETOOLONG, os.strerror(errno.ENAMETOOLONG))
    return target


def _refuse_foreign_entries(given: Path, target: Path) -> None:
    """A report file's name in the folder taken by something else than a file or a symbolic link (a user's folder
    named ``results.json``) is never replaced: replacing would delete it."""
    for name in REPORT_FILES:
        entry = target / name
        if entry.exists() and not entry.is_symlink() and not entry.is_file():
            kind = "a folder" if entry.is_dir() else "not a regular file"
            raise UserError(
                f"--out {str(given)!r}: {str(entry)!r} is {kind}, not a report file; certkit writes "
                f"{' and '.join(REPORT_FILES)} there and will not delete it (move it, or choose another "
                "--out)"
            )


def write_set(out: Path, files: Mapping[str, str | Sequence[str]]) -> None:
    """Write ``files`` (name → text, or its consecutive pieces) as the content of folder ``out``, replacing its
    previous set in one step; never after an interrupt (Ctrl-C: the previous set stays)."""
    raise_if_requested()
    _refuse_foreign_entries(out, out)  # checked before the evaluation too; the folder may have changed since
    parent = out.parent
    _remove_stale(parent)
    new = None
    try:
        new = Path(tempfile.mkdtemp(prefix=f".certkit-{os.getpid()}-", suffix=".new", dir=parent))
        os.chmod(new, 0o777 & ~_umask())
        for name, text in files.items():
            _write_new(new / name, text)
        _sync(new)
        raise_if_requested()
        if not out.exists() and not out.is_symlink():
            os.rename(new, out)
        elif set(os.listdir(out)) <= set(REPORT_FILES):
            _swap(new, out)
        else:
            _replace_each(new, out, files)
            return
    except OSError as exc:
        raise UserError(f"cannot write the report to {str(out)!r}: {exc.strerror or exc}") from None
    finally:
        if new is not None:
            shutil.rmtree(new, ignore_errors=True)  # after a swap: the previous set (symlinks removed, not followed)
    _sync(parent)


def _write_new(path: Path, text: str | Sequence[str]) -> None:
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o666)
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        f.writelines([text] if isinstance(text, str) else text)
        f.flush()
        os.fsync(f.fileno())


def _swap(new: Path, out: Path) -> None:
    """``new`` takes ``out``'s place and ``out``'s content moves to ``new`` (atomic exchange where the kernel has
    it; else two renames, between which ``out`` is briefly absent and its previous set lies at ``*.old``)."""
    libc = ctypes.CDLL(None, use_errno=True)
    rename2 = getattr(libc, "renameat2", None)
    if rename2 is not None and rename2(_AT_FDCWD, bytes(new), _AT_FDCWD, bytes(out), _RENAME_EXCHANGE) == 0:
        return
    old = Path(tempfile.mkdtemp(prefix=f".certkit-{os.getpid()}-", suffix=".old", dir=out.parent))
    os.rmdir(old)
    os.rename(out, old)
    os.rename(new, out)
    os.rename(old, new)


def _replace_each(new: Path, out: Path, files: Mapping[str, object]) -> None:
    for name in sorted(files, key=lambda n: REPORT_FILES.index(n) if n in REPORT_FILES else len(REPORT_FILES)):
        os.replace(new / name, out / name)  # replaces a symlink itself, never its target
    _sync(out)


def _remove_stale(parent: Path) -> None:
    """Temporary folders a killed run left beside its reports (their process no longer exists)."""
    try:
        names = os.listdir(parent)
    except OSError:
        return
    for name in names:
        m = _TEMP.match(name)
        if m and not _alive(int(m[1])):
            shutil.rmtree(parent / name, ignore_errors=True)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _sync(folder: Path) -> None:
    try:
        fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
