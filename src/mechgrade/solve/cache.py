"""The on-disk cache of compiled problems: what deriving a problem with sympy produced, kept so
that solving it again (``mechgrade check`` of an unchanged file) needs no sympy at all: a
kinematics problem's plan (:mod:`.plan`) and symbolic answers (:mod:`.instant`), a dynamics
problem's solutions, for each givens and objectives asked (:mod:`.stored`), and a checked
file's report (:func:`mechgrade.check.check_problem`, keyed by the file's path and bytes).

An entry is named by :func:`problem_key`, a SHA-256 of the loaded problem's canonical text
(its ``repr``: every field, locations included, so a moved line gives messages that point at
the right place), mechgrade's version and a fingerprint of its source files, sympy's version
and :data:`FORMAT`. Keying on the loaded problem rather than the file's bytes also covers
problems made in memory; an upgrade of mechgrade or sympy, or an edit of mechgrade's code,
gives new keys, never a stale entry.

Where: ``$MECHGRADE_CACHE_DIR`` if set (an absolute path), else ``$XDG_CACHE_HOME/mechgrade``,
else ``~/.cache/mechgrade``. ``MECHGRADE_NO_CACHE=1`` turns the cache off (nothing read or
written). The entries are ``<folder>/entries/<64 hex digits>.json``; the cache never reads,
writes or removes anything else but its key, ``<folder>/entries/key``. Its size is bounded
(:func:`prune`): past :data:`MAX_MB` megabytes (``$MECHGRADE_CACHE_MAX_MB``), the entries
used least recently are removed.

The cache only ever makes solving faster; it never decides an answer:

- The folder is private. It is made with mode 0700; one that belongs to another user or that
  others may write (or whose ``entries`` folder or key is such) is not used in this run, and
  :func:`warning` says why once, for the command line to print.
- Entries are authenticated: each starts with an HMAC-SHA256 of its name and content under a
  random key of 32 bytes made once per folder (mode 0600, beside the entries). An entry
  edited, copied from another folder or written by anyone without the key is ignored and
  written again.
- An entry is read only if it is a regular file (opened without following links or waiting
  on a pipe) of at most :data:`MAX_ENTRY_BYTES`; its JSON holds finite numbers only.
- Defence in depth, should the key itself leak: what is read is checked as it is decoded
  (:mod:`mechgrade.codec`), and the only code in an entry, the source sympy's ``lambdify``
  printed for the problem's functions, is compiled only when it is one bounded function of
  numbers (:func:`.generated.numpy_function`).

An entry that is missing, corrupt, truncated, unauthenticated, of another format or key, or
refused by those checks is ignored and written again: it can cost time, never a wrong answer,
a hang or a crash.

>>> import tempfile
>>> from unittest import mock
>>> with mock.patch.dict("os.environ", MECHGRADE_CACHE_DIR=tempfile.mkdtemp(),
...                      MECHGRADE_NO_CACHE="0"):
...     store("a" * 64, {"answer": 42}); load("a" * 64)
{'answer': 42}
"""

from __future__ import annotations

import hashlib
import hmac
import itertools
import json
import math
import os
import re
import secrets
import stat
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any


from .. import __version__
from ..errors import Location, MechgradeError, SettingError
from ..files import write_text

FORMAT = 3
"""The layout of an entry; raised whenever what is stored changes."""

MAX_MB = 200
"""The megabytes of entries the folder is kept under, unless ``$MECHGRADE_CACHE_MAX_MB`` says
otherwise (a number from 0 to :data:`MAX_MB_SETTING`)."""

MAX_MB_SETTING = 1_000_000
"""The largest ``$MECHGRADE_CACHE_MAX_MB`` (a terabyte)."""

MAX_ENTRY_BYTES = 8 * 1024 * 1024
"""The largest entry read or written (the largest of the shipped problems takes 50 kB)."""

PRUNE_EVERY = 100
"""Stores between two looks at the folder's size (the first store of a process looks)."""

ENTRIES = "entries"
"""The cache's own subfolder: the only place it writes, and prunes."""

KEY_FILE = "key"
KEY_BYTES = 32

_ENTRY_NAME = re.compile(r"[0-9a-f]{64}\.json")

def enabled() -> bool:
    """Whether the cache is asked for (``MECHGRADE_NO_CACHE`` unset, empty or ``0``); the
    folder itself may still be refused (:func:`warning`)."""
    return os.environ.get("MECHGRADE_NO_CACHE", "") in ("", "0")


def folder() -> Path:
    """Where the cache is (see the module's docstring); a relative ``$XDG_CACHE_HOME`` is
    ignored, as its specification says. Raises :class:`SettingError` for a
    ``$MECHGRADE_CACHE_DIR`` that is relative or not a folder.

    >>> from unittest import mock
    >>> with mock.patch.dict("os.environ", MECHGRADE_CACHE_DIR="cache"):
    ...     folder()  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechgrade.errors.SettingError: MECHGRADE_CACHE_DIR: expected an absolute path ...
    """
    chosen = os.environ.get("MECHGRADE_CACHE_DIR")
    if chosen:
        where = Location(field="MECHGRADE_CACHE_DIR")
        if not os.path.isabs(chosen):
            raise SettingError(f"expected an absolute path to a folder, found {chosen!r}; "
                               f"write it in full ({os.path.abspath(chosen)!r}), or unset it "
                               "for the default", where=where)
        if os.path.exists(chosen) and not os.path.isdir(chosen):
            raise SettingError(f"expected a folder, found a file that is not one: {chosen!r}; "
                               "name a folder (it is made if missing), or unset it for the "
                               "default", where=where)
        return Path(chosen)
    base = os.environ.get("XDG_CACHE_HOME", "")
    if not os.path.isabs(base):
        base = os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "mechgrade"


def limit() -> int:
    """The bytes of entries the folder is kept under (:data:`MAX_MB` megabytes, or
    ``$MECHGRADE_CACHE_MAX_MB``); raises :class:`SettingError` for a value that is not a
    number of megabytes from 0 to :data:`MAX_MB_SETTING`.

    >>> from unittest import mock
    >>> with mock.patch.dict("os.environ", MECHGRADE_CACHE_MAX_MB="0.5"):
    ...     limit()
    524288
    """
    text = os.environ.get("MECHGRADE_CACHE_MAX_MB", "").strip()
    if not text:
        return MAX_MB * 1024 * 1024
    try:
        megabytes = float(text)
    except ValueError:
        megabytes = math.nan
    if not 0 <= megabytes <= MAX_MB_SETTING:  # nan and inf too
        raise SettingError(f"expected a number of megabytes from 0 to {MAX_MB_SETTING}, found "
                           f"{text!r:.40}; set it to a number such as {MAX_MB}, or unset it for "
                           f"the default ({MAX_MB})",
                           where=Location(field="MECHGRADE_CACHE_MAX_MB"))
    return int(megabytes * 1024 * 1024)


# ---------------------------------------------------------------------------- the folder


@dataclass(frozen=True)
class _Folder:
    """The cache as this process uses it: its entries folder and key (``entries`` None: not
    used), its size bound, and why not, if it is not (a warning, or a bad setting)."""

    entries: str | None = None
    secret: bytes = b""
    bound: int = 0
    warning: str | None = None
    error: SettingError | None = None


class _Refused(Exception):
    """A folder or key the cache will not use; the message says which, why and the fix."""


def warning() -> str | None:
    """Why the cache is not used in this process, once worked out (``None``: it is, or it is
    turned off): a folder or key that another user owns or may write, or that cannot be made.
    Raises :class:`SettingError` for a cache setting that is not valid. The command line
    prints it once, before solving.

    >>> import tempfile
    >>> from unittest import mock
    >>> shared = tempfile.mkdtemp(); os.chmod(shared, 0o777)
    >>> with mock.patch.dict("os.environ", MECHGRADE_CACHE_DIR=shared, MECHGRADE_NO_CACHE="0"):
    ...     print(warning())  # doctest: +ELLIPSIS
    cache folder /... may be written by other users (mode 777): not using the cache in this run (...)
    """
    state = _opened()
    if state.error is not None:
        raise state.error
    return state.warning


def _opened() -> _Folder:
    environ = os.environ
    return _state(enabled(), environ.get("MECHGRADE_CACHE_DIR"), environ.get("XDG_CACHE_HOME"),
                  environ.get("HOME"), environ.get("MECHGRADE_CACHE_MAX_MB"))


@lru_cache(maxsize=8)
def _state(on: bool, *settings: str | None) -> _Folder:  # noqa: ARG001 - the cache key
    """The folder for these settings (the arguments are only the cache's key), checked and
    its key read or made once per process."""
    if not on:
        return _Folder()
    try:
        root, bound = folder(), limit()
    except SettingError as err:
        return _Folder(error=err)
    try:
        entries = _private_folder(root)
        return _Folder(entries, _secret(entries), bound)
    except _Refused as refused:
        return _Folder(warning=str(refused))


def _private_folder(root: Path) -> str:
    """The entries folder inside ``root``, each made private if missing, checked if not."""
    try:
        os.makedirs(root, mode=0o700, exist_ok=True)
        _check_private(os.stat(root), root, "cache folder")
        entries = os.path.join(root, ENTRIES)
        try:
            os.mkdir(entries, 0o700)
        except FileExistsError:
            pass
        fd = os.open(entries, os.O_RDONLY | _NOFOLLOW | getattr(os, "O_DIRECTORY", 0))
    except OSError as err:
        raise _Refused(f"cannot use the cache folder {root} ({err.strerror or err}): not "
                       "using the cache in this run (set MECHGRADE_CACHE_DIR to a folder of "
                       "your own, or MECHGRADE_NO_CACHE=1)") from None
    try:
        _check_private(os.fstat(fd), entries, "cache folder")
    finally:
        os.close(fd)
    return entries


_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_READ = os.O_RDONLY | _NOFOLLOW | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)


def _check_private(info: os.stat_result, path, what: str) -> None:
    if not stat.S_ISDIR(info.st_mode):
        raise _Refused(f"{what} {path} is not a folder: not using the cache in this run "
                       "(remove it, or set MECHGRADE_CACHE_DIR to a folder of your own)")
    _check_owner(info, path, what)
    if info.st_mode & 0o022:
        raise _Refused(f"{what} {path} may be written by other users (mode "
                       f"{stat.S_IMODE(info.st_mode):o}): not using the cache in this run "
                       f"(make it private with 'chmod 700 {path}', or set MECHGRADE_CACHE_DIR "
                       "to a private folder)")


def _check_owner(info: os.stat_result, path, what: str) -> None:
    me = os.geteuid() if hasattr(os, "geteuid") else info.st_uid
    if info.st_uid != me:
        raise _Refused(f"{what} {path} belongs to another user (uid {info.st_uid}): not using "
                       "the cache in this run (set MECHGRADE_CACHE_DIR to a folder of your "
                       "own)")


def _secret(entries: str) -> bytes:
    """The folder's key, made (atomically: a key is never replaced) if there is none."""
    path = os.path.join(entries, KEY_FILE)
    for _ in range(3):
        try:
            fd = os.open(path, _READ)
        except FileNotFoundError:
            _make_secret(entries, path)
            continue
        except OSError as err:  # a link (ELOOP), or no permission
            raise _Refused(f"cache key {path} cannot be read ({err.strerror or err}): not "
                           f"using the cache in this run (delete it: a new one is made)") \
                from None
        try:
            info = os.fstat(fd)
            secret = os.read(fd, KEY_BYTES + 1) if stat.S_ISREG(info.st_mode) else b""
        finally:
            os.close(fd)
        if not stat.S_ISREG(info.st_mode) or stat.S_IMODE(info.st_mode) & 0o077 \
                or len(secret) != KEY_BYTES:
            raise _Refused(f"cache key {path} is not a private file of {KEY_BYTES} bytes "
                           f"(found {_described(info, len(secret))}): not using the cache in "
                           "this run (delete it: a new one is made)")
        _check_owner(info, path, "cache key")
        return secret
    raise _Refused(f"cache key {path} keeps disappearing: not using the cache in this run")


def _described(info: os.stat_result, size: int) -> str:
    if not stat.S_ISREG(info.st_mode):
        return "a folder" if stat.S_ISDIR(info.st_mode) else "a special file"
    return f"mode {stat.S_IMODE(info.st_mode):o}, {size} bytes"


def _make_secret(entries: str, path: str) -> None:
    """A new key at ``path``, unless another process made one meanwhile (theirs is kept)."""
    temporary = os.path.join(entries, f".key.{os.getpid()}.{secrets.token_hex(8)}.tmp")
    try:
        fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | _NOFOLLOW, 0o600)
        try:
            os.write(fd, secrets.token_bytes(KEY_BYTES))
        finally:
            os.close(fd)
        try:
            os.link(temporary, path)
        except FileExistsError:
            pass
    except OSError as err:
        raise _Refused(f"cannot make the cache key {path} ({err.strerror or err}): not using "
                       "the cache in this run") from None
    finally:
        try:
            os.unlink(temporary)
        except OSError:
            pass


# ---------------------------------------------------------------------------- entries


def problem_key(problem) -> str | None:
    """The key of a problem's entries, or ``None`` when it has no canonical text (a field
    whose ``repr`` is an object's identity) and so cannot be cached.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
    >>> len(problem_key(problem)), problem_key(problem) == problem_key(problem)
    (64, True)
    """
    text = repr(problem)
    if " at 0x" in text:
        return None
    return digest(*code_key(), text)


def used_problem_key(problem) -> str | None:
    """:func:`problem_key` where the cache is on, else ``None``: a key no entry is read or
    stored under is not worked out (it hashes the whole problem).

    >>> from unittest import mock
    >>> with mock.patch.dict("os.environ", MECHGRADE_NO_CACHE="1"):
    ...     used_problem_key(object()) is None
    True
    """
    return problem_key(problem) if enabled() else None


def code_key(*libraries: str) -> tuple[Any, ...]:
    """What an entry's key names of the code that made it: :data:`FORMAT`, mechgrade's
    version and source files, sympy's version, and each of ``libraries``' (import names)."""
    return (FORMAT, __version__, _source_fingerprint(), _sympy_version(),
            *(package_version(name, "version.py") for name in libraries))


def digest(*parts: Any) -> str:
    """SHA-256 (hex) of ``parts`` as JSON: the name of one entry."""
    return hashlib.sha256(json.dumps(parts, default=repr).encode()).hexdigest()


def _signature(secret: bytes, key: str, body: bytes) -> bytes:
    """An entry's first line: the HMAC-SHA256 (hex) of its name and content."""
    mac = hmac.new(secret, key.encode() + b"\n", hashlib.sha256)
    mac.update(body)
    return mac.hexdigest().encode()


def load(key: str) -> Any:
    """The data stored under ``key``, or ``None`` when there is none this cache wrote (see
    the module's docstring). An entry read is marked used now (its modification time), for
    :func:`prune`."""
    state = _opened()
    if state.entries is None:
        return None
    path = os.path.join(state.entries, _entry_name(key))
    try:
        fd = os.open(path, _READ)
    except OSError:
        return None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or info.st_size > MAX_ENTRY_BYTES:
            return None
        with open(fd, "rb", closefd=False) as handle:
            raw = handle.read(MAX_ENTRY_BYTES + 1)
        if raw[64:65] != b"\n" or len(raw) > MAX_ENTRY_BYTES or not hmac.compare_digest(
                raw[:64], _signature(state.secret, key, raw[65:])):
            return None
        try:
            os.utime(fd if os.utime in os.supports_fd else path)
        except OSError:
            pass  # a read-only folder: it was read all the same
    except OSError:
        return None
    finally:
        os.close(fd)
    try:
        return json.loads(raw[65:], parse_float=_finite, parse_int=_whole,
                          parse_constant=_not_a_number)
    except (ValueError, RecursionError):
        return None


def _finite(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise ValueError("not a finite number")
    return value


def _whole(text: str) -> int:
    if len(text) > 17:  # MAX_INTEGER has 16 digits
        raise ValueError("too large a whole number")
    return int(text)


def _not_a_number(text: str) -> float:
    raise ValueError(f"{text} is not a finite number")


def _entry_name(key: str) -> str:
    name = f"{key}.json"
    if not _ENTRY_NAME.fullmatch(name):
        raise ValueError(f"expected 64 hexadecimal digits, found {key!r}")
    return name


def store(key: str, data: Any) -> None:
    """Keep ``data`` (plain JSON, finite numbers) under ``key``, written atomically; a cache
    that cannot be written (a read-only home, a full disk) is no error: the next run derives
    again. Every :data:`PRUNE_EVERY` stores of a process, the first included, the folder is
    pruned."""
    name = _entry_name(key)
    state = _opened()
    if state.entries is None:
        return
    try:
        body = json.dumps(data, separators=(",", ":"), allow_nan=False).encode()
    except ValueError:
        return  # a number that is not finite: not kept
    if len(body) + 65 > MAX_ENTRY_BYTES:
        return
    try:
        write_text(os.path.join(state.entries, name),
                   (_signature(state.secret, key, body) + b"\n" + body).decode())
    except (OSError, MechgradeError):
        return
    if next(_stores) % PRUNE_EVERY == 0:
        prune(state.bound)


_stores = itertools.count()


def prune(bound: int) -> None:
    """When the entries take more than ``bound`` bytes, remove the least recently used ones
    (oldest modification time first) until they take three quarters of it, so that the next
    stores do not prune again at once. Only the cache's own entries count and go (regular
    files named as :func:`store` names them, in its ``entries`` folder): nothing else there
    or beside it is touched. Another process may store, read or prune meanwhile: an entry
    gone already is no error, and one removed under a reader is a miss.

    >>> import tempfile, time
    >>> from unittest import mock
    >>> with mock.patch.dict("os.environ", MECHGRADE_CACHE_DIR=tempfile.mkdtemp(),
    ...                      MECHGRADE_NO_CACHE="0"):
    ...     for name in "abc":
    ...         store(name * 64, "x" * 1000)
    ...         os.utime(folder() / ENTRIES / f"{name * 64}.json", (0, ord(name)))
    ...     prune(2500); sorted(p.name[0] for p in (folder() / ENTRIES).glob("*.json"))
    ['c']
    """
    entries_folder = _opened().entries
    if entries_folder is None:
        return
    found = []
    try:
        with os.scandir(entries_folder) as entries:
            for entry in entries:
                if _ENTRY_NAME.fullmatch(entry.name):
                    try:
                        info = entry.stat(follow_symlinks=False)
                    except OSError:
                        continue  # removed meanwhile
                    if stat.S_ISREG(info.st_mode):
                        found.append((info.st_mtime_ns, info.st_size, entry.path))
    except OSError:
        return
    total = sum(size for _, size, _ in found)
    if total <= bound:
        return
    for _, size, path in sorted(found):
        if total <= bound * 3 // 4:
            break
        try:
            os.remove(path)
        except FileNotFoundError:
            pass  # another process pruned it
        except OSError:
            continue
        total -= size


def _sympy_version() -> str:
    return package_version("sympy", "release.py")


@lru_cache(maxsize=16)
def package_version(name: str, release: str) -> str:
    """A package's version as read from its ``release`` file (without importing it: asking
    the package metadata takes as long as a whole warm check), and the size and modification
    time of its ``__init__.py``, which any upgrade rewrites."""
    import importlib.util

    spec = importlib.util.find_spec(name)
    if spec is None or spec.origin is None:
        return "none"
    try:
        found = re.search(r"^(?:__version__|version)\s*=\s*['\"]([^'\"]+)",
                          Path(spec.origin).with_name(release).read_text(), re.MULTILINE)
    except OSError:
        found = None
    info = os.stat(spec.origin)
    return f"{found.group(1) if found else ''}:{info.st_size}:{info.st_mtime_ns}"


@lru_cache(maxsize=1)
def _source_fingerprint() -> str:
    """Sizes and modification times of mechgrade's own source files (and its schema): an
    edited derivation (a working copy, not only a new version) never reads an entry made by
    the old code."""
    stamps: list[tuple[str, int, int]] = []

    def scan(folder: str, prefix: str) -> None:
        with os.scandir(folder) as found:
            for entry in sorted(found, key=lambda e: e.name):
                if entry.name.endswith((".py", ".json")) and entry.is_file():
                    info = entry.stat()
                    stamps.append((prefix + entry.name, info.st_size, info.st_mtime_ns))
                elif entry.name != "__pycache__" and entry.is_dir():
                    scan(entry.path, f"{prefix}{entry.name}/")

    scan(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "")
    return digest(stamps)
