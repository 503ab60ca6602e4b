"""A command's output folder (``--out``): one run's outputs, whole, recorded, one run at a time.

A run never writes into ``--out`` itself. It writes into a fresh folder beside it, and when every
file is there the new folder takes the place of the old one in one ``rename`` (Linux swaps the
two; elsewhere two renames, which the next run completes if it was cut between them). So the
folder always holds one run's outputs: a run that fails or is killed leaves the previous outputs
as they were, and a regrade of fewer students leaves no page of the others.

* The instructor's own files in ``--out`` (a class report, notes, an LMS export written there)
  are kept: they come along into the new folder (hard links, so nothing is copied or lost, even
  when a run is killed). A previous run's file that this run does not write is removed and
  listed. mechgrade tells them apart by ``manifest.json``, which records each run: mechgrade's
  version, the command and its arguments, when it ran, its inputs with their SHA-256, the files
  it wrote, the files it kept and the ones it removed. A folder written before manifests
  existed is recognised by its outputs' names (:attr:`OutputKind.patterns`).
* A folder holding something else (no manifest, none of the command's outputs: a course folder,
  ``~``), the outputs of another command, or the current folder, is refused, never replaced.
* A lock (``fcntl.flock`` on ``.<name>.mechgrade-lock`` beside the folder) lets one run at a time
  write a folder; a second is refused at once, with the process id of the first.

>>> import tempfile, pathlib
>>> out = pathlib.Path(tempfile.mkdtemp()) / "out"
>>> kind = OutputKind("mechgrade demo", "a.txt", ("a.txt", "b.txt"))
>>> with claim(out, kind) as folder:
...     _ = (folder.staging / "a.txt").write_text("1")
...     _ = (folder.staging / "b.txt").write_text("2")
...     done = folder.commit({}, inputs=())
>>> sorted(p.name for p in out.iterdir()), done.removed
(['a.txt', 'b.txt', 'manifest.json'], ())
>>> with claim(out, kind) as folder:
...     _ = (folder.staging / "a.txt").write_text("1")
...     done = folder.commit({}, inputs=())
>>> sorted(p.name for p in out.iterdir()), done.removed
(['a.txt', 'manifest.json'], ('b.txt',))
"""

from __future__ import annotations

import ctypes
import errno
import fnmatch
import hashlib
import json
import os
import secrets
import shutil
import stat
import sys
from contextlib import contextmanager
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path
from typing import Iterator

from . import __version__
from .errors import Location, OutputError
from .files import replacing, write_json

MANIFEST = "manifest.json"
FORMAT = "mechgrade outputs 1"


@dataclass(frozen=True)
class OutputKind:
    """What a command writes into its folder: the command (as the manifest names it), the file
    that marks that command's outputs in a folder written before manifests existed (``None``:
    such a folder is not recognised) and the patterns (``fnmatch``, relative paths) of every
    file it writes, by which such a folder is read."""

    command: str
    signature: str | None
    patterns: tuple[str, ...]

    def writes(self, relative: str) -> bool:
        """Whether ``relative`` is a name this command writes.

        >>> OutputKind("x", "r.json", ("r.json", "feedback/*.md")).writes("feedback/a.md")
        True
        """
        return any(fnmatch.fnmatchcase(relative, pattern) and
                   relative.count("/") == pattern.count("/") for pattern in self.patterns)


@dataclass(frozen=True)
class Committed:
    """What :meth:`OutputFolder.commit` did: the files written (relative, sorted), the
    instructor's files kept, the previous run's files removed, and the leftovers of an
    interrupted run cleared before this one (``notes``)."""

    files: tuple[str, ...]
    kept: tuple[str, ...]
    removed: tuple[str, ...]
    notes: tuple[str, ...] = ()


def check_apart(out: str | os.PathLike, submissions: str | os.PathLike) -> None:
    """Refuse an ``--out`` that is the submissions folder, inside it (the next run would grade the
    outputs as students' work) or holding it (a run replaces ``--out`` whole).

    >>> check_apart("class/out", "class")
    Traceback (most recent call last):
    ...
    mechgrade.errors.OutputError: class/out: --out: expected a folder outside the submissions folder, found a folder inside class (the next run would grade the outputs as students' work); choose another --out
    """
    target, folder = _real(out), _real(submissions)
    if target == folder or folder in target.parents:
        found = ("the submissions folder itself" if target == folder
                 else f"a folder inside {submissions}")
        raise OutputError(f"expected a folder outside the submissions folder, found {found} "
                          f"(the next run would grade the outputs as students' work); choose "
                          f"another --out", where=Location(str(out), field="--out"))
    if target in folder.parents:
        raise OutputError(f"expected a folder that does not hold the submissions folder, found "
                          f"{submissions} inside it (a run replaces --out whole); choose "
                          f"another --out", where=Location(str(out), field="--out"))


def _real(path: str | os.PathLike) -> Path:
    return Path(os.path.abspath(path)).resolve()


class OutputFolder:
    """A claimed output folder (see :func:`claim`): write into :attr:`staging`, then
    :meth:`commit`."""

    def __init__(self, shown: str, target: Path, kind: OutputKind, started: str) -> None:
        self.shown = shown  # the folder as the user named it, for messages
        self.target = target
        self.kind = kind
        self.started = started
        self.notes: list[str] = []
        self.previous: frozenset[str] = frozenset()  # the previous run's files
        self.theirs: tuple[str, ...] = ()  # the instructor's files (and empty folders, "x/")
        self.staging = target  # replaced by the fresh folder once made
        self.committed: Committed | None = None

    def commit(self, arguments: dict, *, inputs: tuple[tuple[str, str | os.PathLike], ...]
               ) -> Committed:
        """Put the instructor's files beside what was written in :attr:`staging`, record the run
        in ``manifest.json`` (the command's ``arguments``; ``inputs``: the ``(role, path)`` of
        each file read) and swap the new folder in. Raises :class:`OutputError` (then ``--out``
        is left as it was)."""
        files = tuple(sorted(_files(self.staging)))
        clash = sorted({*files, MANIFEST} & set(self.theirs))
        if clash:
            raise OutputError(f"expected no file of yours where this run writes its outputs, "
                              f"found {_listed(clash)} (kept as they are: mechgrade never "
                              f"replaces a file it did not write); move them away and run "
                              f"again", where=Location(self.shown, field="--out"))
        old = self.target if self.target.is_dir() else None
        removed = tuple(sorted(self.previous - set(files)))
        if old is not None:
            self._keep(old)
        record = {
            "format": FORMAT,
            "mechgrade": __version__,
            "command": self.kind.command,
            "arguments": arguments,
            "started": self.started,
            "finished": _now(),
            "inputs": [{"role": role, "path": str(path), "sha256": _sha256(path)}
                       for role, path in inputs],
            "files": list(files),
            "kept": [name for name in self.theirs if not name.endswith("/")],
            "removed": list(removed),
        }
        write_json(self.staging / MANIFEST, record)
        if old is not None:
            for inner in _folders((*files, *self.theirs)):
                if (old / inner).is_dir():
                    _same_access(old / inner, self.staging / inner)
        self._swap(old is not None)
        self.committed = Committed(files, tuple(record["kept"]), removed, tuple(self.notes))
        return self.committed

    def _keep(self, old: Path) -> None:
        """Hard-link the instructor's files (and recreate their empty folders) into staging."""
        for name in self.theirs:
            source, copy = old / name, self.staging / name
            try:
                if name.endswith("/"):
                    copy.mkdir(parents=True, exist_ok=True)
                    continue
                copy.parent.mkdir(parents=True, exist_ok=True)
                _link(source, copy)
            except OSError as exc:
                raise OutputError(f"cannot keep this file of yours in the new outputs "
                                  f"({exc.strerror or exc}); --out is left as it was",
                                  where=Location(str(Path(self.shown) / name))) from None

    def _swap(self, replacing: bool) -> None:
        try:
            if not replacing:
                os.rename(self.staging, self.target)
                return
            if _exchange(self.staging, self.target):
                shutil.rmtree(self.staging, ignore_errors=True)  # now the previous outputs
                return
            aside = _sibling(self.target, "old")
            os.rename(self.target, aside)
            os.rename(self.staging, self.target)  # cut here, the next run puts 'aside' back
            shutil.rmtree(aside, ignore_errors=True)
        except OSError as exc:
            raise OutputError(f"cannot put the new outputs in place ({exc.strerror or exc}); "
                              f"--out is left as it was",
                              where=Location(self.shown, field="--out")) from None


@contextmanager
def claim(out: str | os.PathLike, kind: OutputKind) -> Iterator[OutputFolder]:
    """Lock ``out`` for this run, check it may be replaced, and make the fresh folder to write
    into; on leaving, a folder that was not committed is removed and the lock released.

    Raises :class:`OutputError` for a folder another run is writing, one holding what mechgrade
    did not write and cannot tell from an instructor's additions, the current folder or one
    holding it, or one that cannot be made."""
    shown = str(out)
    target = _real(out)
    if target.exists() and not target.is_dir():
        raise OutputError("expected a folder, found a file", where=Location(shown, field="--out"))
    if target == _real(".") or target in _real(".").parents:
        raise OutputError("expected a folder that does not hold the current folder, found the "
                          "current folder inside it (a run replaces --out whole); run from "
                          "another folder, or choose another --out",
                          where=Location(shown, field="--out"))
    made = _make_parents(target.parent, shown)
    folder = OutputFolder(shown, target, kind, _now())
    lock = None
    try:
        lock = _lock(target, shown)
        folder.notes.extend(_recover(target))
        folder.previous, folder.theirs = _read_previous(target, kind, shown)
        folder.staging = _sibling(target, "new")
        try:
            folder.staging.mkdir()
        except OSError as exc:
            raise OutputError(f"cannot create the output folder ({exc.strerror or exc})",
                              where=Location(shown, field="--out")) from None
        if target.is_dir():
            with replacing(folder.staging, target):
                yield folder
        else:
            yield folder
    finally:
        if folder.committed is None and folder.staging != target:
            shutil.rmtree(folder.staging, ignore_errors=True)
        if lock is not None:
            _unlock(target, lock)
        if folder.committed is None:
            for parent in made:  # the folders made for a run that wrote nothing
                try:
                    parent.rmdir()
                except OSError:
                    break


def _now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="milliseconds")


def _make_parents(parent: Path, shown: str) -> list[Path]:
    """Make ``parent`` and the folders above it as needed; those made, innermost first."""
    missing = [p for p in [parent, *parent.parents] if not p.exists()]
    try:
        parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"cannot create the output folder ({exc.strerror or exc})",
                          where=Location(shown, field="--out")) from None
    return missing


def _lock_path(target: Path) -> Path:
    return target.with_name(f".{target.name}.mechgrade-lock")


def _lock(target: Path, shown: str) -> int:
    """Hold the lock of ``target``: an open file with an exclusive ``flock`` on it, holding
    this process's id. A lock file removed and made again by another run between our open
    and our ``flock`` is opened again (so two runs can never hold two different files)."""
    import fcntl

    path = _lock_path(target)
    while True:
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT | getattr(os, "O_CLOEXEC", 0), 0o666)
        except OSError as exc:
            raise OutputError(f"cannot create {path.name} beside it ({exc.strerror or exc}): "
                              f"a run locks --out and builds its outputs beside it, so the "
                              f"folder holding --out must be writable",
                              where=Location(shown, field="--out")) from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            holder = os.read(fd, 32).decode("ascii", "replace").strip()
            os.close(fd)
            if exc.errno not in (errno.EAGAIN, errno.EACCES):
                raise OutputError(f"cannot lock the folder ({exc.strerror or exc})",
                                  where=Location(shown, field="--out")) from None
            who = f"mechgrade process {holder}" if holder.isdigit() else "another mechgrade run"
            raise OutputError(f"expected a folder no other run is writing, found {who} "
                              f"writing it; wait for that run to end, or choose another --out",
                              where=Location(shown, field="--out")) from None
        try:
            same = os.path.samestat(os.fstat(fd), os.stat(path))
        except OSError:
            same = False
        if same:
            os.ftruncate(fd, 0)
            os.write(fd, f"{os.getpid()}\n".encode("ascii"))
            _LOCKS.add(fd)
            return fd
        os.close(fd)


def _unlock(target: Path, fd: int) -> None:
    try:
        _lock_path(target).unlink()  # while still holding it: see _lock
    except OSError:
        pass
    _LOCKS.discard(fd)
    os.close(fd)


_LOCKS: set[int] = set()


def _forget_locks_in_child() -> None:
    # A worker forked while the lock is held must not keep the folder locked (a lock is held
    # while any process has the file open); closing its copy leaves the parent's lock alone.
    for fd in _LOCKS:
        try:
            os.close(fd)
        except OSError:
            pass
    _LOCKS.clear()


os.register_at_fork(after_in_child=_forget_locks_in_child)


def _sibling(target: Path, role: str) -> Path:
    return target.with_name(f".{target.name}.mechgrade-{role}.{secrets.token_hex(4)}")


def _recover(target: Path) -> list[str]:
    """Clear what an interrupted run left beside ``target`` (we hold the lock, so no run is
    writing them): a previous outputs folder set aside just before the swap is put back if
    ``target`` is missing, and every unfinished new folder is removed."""
    notes: list[str] = []
    prefix = f".{target.name}.mechgrade-"
    try:
        leftovers = sorted(p for p in target.parent.iterdir() if p.name.startswith(prefix)
                           and p.name[len(prefix):].split(".")[0] in ("new", "old"))
    except OSError:
        return notes
    for path in leftovers:
        if path.name.startswith(prefix + "old.") and not target.exists():
            try:
                os.rename(path, target)
            except OSError:
                continue  # left where it is, and said below
            notes.append(f"put back the outputs an interrupted run had set aside ({path.name})")
    for path in leftovers:
        if path.exists():
            shutil.rmtree(path, ignore_errors=True)
            notes.append(f"removed what an interrupted run left ({path.name})")
    return notes


def _read_previous(target: Path, kind: OutputKind, shown: str
                   ) -> tuple[frozenset[str], tuple[str, ...]]:
    """The previous run's files in ``target`` and the instructor's (files, and empty folders
    as ``name/``); refuses a folder that is neither."""
    entries = _entries(target) if target.is_dir() else []
    if not entries:
        return frozenset(), ()
    present = [name for name in entries if not name.endswith("/")]
    manifest = target / MANIFEST
    recorded = _manifest_files(manifest, kind, shown) if manifest.is_file() else None
    if recorded is not None:
        ours = frozenset(recorded) | {MANIFEST}
    elif kind.signature is not None and (target / kind.signature).is_file():
        ours = frozenset(name for name in present if kind.writes(name))
    else:
        top = sorted({name.split("/")[0] + ("/" if "/" in name else "") for name in entries})
        raise OutputError(f"expected a new or empty folder, or one '{kind.command}' wrote before "
                          f"(it holds {MANIFEST}), found {len(top)} "
                          f"{'entry' if len(top) == 1 else 'entries'} of something else "
                          f"({_listed(top)}); choose another --out",
                          where=Location(shown, field="--out"))
    theirs = tuple(name for name in entries if name not in ours and not (
        name.endswith("/") and any(other.startswith(name) for other in ours)))
    return frozenset(name for name in present if name in ours) - {MANIFEST}, theirs


def _manifest_files(path: Path, kind: OutputKind, shown: str) -> list[str] | None:
    """The files a previous run's manifest lists; ``None`` when it is not mechgrade's."""
    try:
        data = json.loads(path.read_bytes().decode("utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("format") != FORMAT or \
            not isinstance(data.get("files"), list):
        return None
    if data.get("command") != kind.command:
        raise OutputError(f"expected a folder of '{kind.command}' outputs, found the outputs of "
                          f"'{data.get('command')}' ({MANIFEST}); choose another --out",
                          where=Location(shown, field="--out"))
    return [name for name in data["files"] if isinstance(name, str)]


def _entries(folder: Path) -> list[str]:
    """Every file (and link, and other entry) below ``folder`` as a relative POSIX path, and
    every empty folder as ``name/``; links are not followed."""
    found: list[str] = []

    def unreadable(err: OSError) -> None:  # never leave a folder of theirs behind unseen
        raise OutputError(f"expected to read every entry of the output folder, found one that "
                          f"cannot be read ({err.strerror or err})",
                          where=Location(str(err.filename))) from None

    for root, dirs, files in os.walk(folder, onerror=unreadable):
        rel = os.path.relpath(root, folder).replace(os.sep, "/")
        prefix = "" if rel == "." else rel + "/"
        for name in list(dirs):
            if os.path.islink(os.path.join(root, name)):
                dirs.remove(name)
                files.append(name)
        found.extend(prefix + name for name in files)
        if not dirs and not files and prefix:
            found.append(prefix)
    return sorted(found)


def _folders(names) -> list[str]:
    """Every folder holding one of ``names`` (relative POSIX paths; ``x/``: the folder x), the
    top one as ``"."``.

    >>> _folders(["a.txt", "f/b.md", "f/c.md", "x/y/z", "e/"])
    ['.', 'e', 'f', 'x', 'x/y']
    """
    found = {"."}
    for inner in {name.rstrip("/").rpartition("/")[0] if not name.endswith("/") else
                  name.rstrip("/") for name in names}:
        while inner and inner not in found:
            found.add(inner)
            inner = inner.rpartition("/")[0]
    return sorted(found)


def _files(folder: Path) -> list[str]:
    return [name for name in _entries(folder) if not name.endswith("/") and name != MANIFEST]


def _link(source: Path, copy: Path) -> None:
    """``copy`` made the same file as ``source`` (a hard link; a copy where links are
    impossible, for a regular file or a symbolic link)."""
    try:
        os.link(source, copy, follow_symlinks=False)
        return
    except OSError as exc:
        if exc.errno not in (errno.EXDEV, errno.EPERM, errno.ENOTSUP, errno.EOPNOTSUPP,
                             errno.EMLINK):
            raise
    if source.is_symlink():
        os.symlink(os.readlink(source), copy)
    elif stat.S_ISREG(source.lstat().st_mode):
        shutil.copy2(source, copy)
    else:
        raise OSError(errno.ENOTSUP, "neither a regular file nor a link, and hard links are "
                                     "not possible here")


def _same_access(old: Path, new: Path) -> None:
    """Give ``new`` the permissions (and group) the instructor set on ``old``."""
    try:
        info = old.stat()
        os.chmod(new, stat.S_IMODE(info.st_mode))
        if new.stat().st_gid != info.st_gid:
            os.chown(new, -1, info.st_gid)
    except OSError:
        pass


RENAME_EXCHANGE = 2  # from <linux/fs.h>
AT_FDCWD = -100


def _exchange(new: Path, target: Path) -> bool:
    """Swap ``new`` and ``target`` in one step (Linux ``renameat2``); ``False`` where that is
    not available."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        renameat2 = libc.renameat2
    except (OSError, AttributeError):
        return False
    if renameat2(AT_FDCWD, os.fsencode(new), AT_FDCWD, os.fsencode(target),
                 RENAME_EXCHANGE) == 0:
        return True
    code = ctypes.get_errno()
    if code in (errno.EINVAL, errno.ENOSYS, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False  # a file system that cannot swap: two renames
    raise OSError(code, os.strerror(code))


def _sha256(path: str | os.PathLike) -> str | None:
    digest = hashlib.sha256()
    try:
        with open(path, "rb") as handle:
            for block in iter(lambda: handle.read(1 << 20), b""):
                digest.update(block)
    except OSError:
        return None
    return digest.hexdigest()


MAX_NAMED = 5


def _listed(names: list[str]) -> str:
    shown = ", ".join(names[:MAX_NAMED])
    return shown + (f" and {len(names) - MAX_NAMED} more" if len(names) > MAX_NAMED else "")
