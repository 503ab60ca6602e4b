"""Reading a user's text file, and writing every output file, each through one function.

Reading: one clear message for every way a file can fail.

>>> from mechgrade.errors import SpecError
>>> read_text("no/such/file.yaml", what="a problem file", error=SpecError)
Traceback (most recent call last):
...
mechgrade.errors.SpecError: no/such/file.yaml: expected a problem file, found no such file

Writing: every string that reaches an output file passes :func:`clean_text` first, so no writer
can fail on what a student typed or on a folder name that is not UTF-8; files are written
through a temporary file and ``os.replace`` with the mode ``open()`` would give them.
"""

from __future__ import annotations

import errno
import itertools
import json
import os
import re
import stat
import unicodedata
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator

from .errors import Location, MechgradeError, OutputError

MAX_BYTES = 1_000_000


def read_text(path: str | Path, *, what: str, error: type[MechgradeError],
              max_bytes: int = MAX_BYTES, hint: str = "") -> str:
    """The UTF-8 text (BOM allowed) of ``path``, or ``error`` saying what was found instead.

    ``what`` names the expected file ("a roster CSV file"); ``hint`` is added to the encoding
    message (for example how to save a spreadsheet as UTF-8).
    """
    name = str(path)
    try:
        # Opened without blocking and checked on the open descriptor: a FIFO (or a device) in
        # place of the file is refused, never waited on or read without end.
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
        with os.fdopen(fd, "rb") as handle:
            info = os.fstat(handle.fileno())
            if stat.S_ISDIR(info.st_mode):
                raise error(f"expected {what}, found a folder", where=Location(name))
            if not stat.S_ISREG(info.st_mode):
                raise error(f"expected {what}, found {_special_kind(info.st_mode)}",
                            where=Location(name))
            if info.st_size > max_bytes:
                raise error(f"expected {what} of at most {max_bytes} bytes, found "
                            f"{info.st_size} bytes", where=Location(name))
            data = handle.read(max_bytes + 1)
    except FileNotFoundError:
        raise error(f"expected {what}, found no such file", where=Location(name)) from None
    except IsADirectoryError:
        raise error(f"expected {what}, found a folder", where=Location(name)) from None
    except OSError as exc:
        raise error(f"cannot read the file ({exc.strerror or exc})", where=Location(name)) \
            from None
    if len(data) > max_bytes:
        raise error(f"expected {what} of at most {max_bytes} bytes, found a larger file",
                    where=Location(name))
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise error(f"expected UTF-8 text{hint}, found byte 0x{data[exc.start]:02x}, which is "
                    "not UTF-8", where=Location(name, line)) from None


def _special_kind(mode: int) -> str:
    """What a path that is no regular file or folder is, in words.

    >>> _special_kind(stat.S_IFIFO)
    'a FIFO (named pipe), not a regular file'
    """
    kinds = ((stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISSOCK, "a socket"),
             (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"))
    kind = next((noun for test, noun in kinds if test(mode)), "a special file")
    return f"{kind}, not a regular file"


_SURROGATE = re.compile("[\ud800-\udfff]")


def _escape_surrogate(match: re.Match) -> str:
    code = ord(match.group())
    # Python decodes a byte that is not UTF-8 (a file name, surrogateescape) as U+DC80..U+DCFF.
    return f"\\x{code - 0xDC00:02x}" if 0xDC80 <= code <= 0xDCFF else f"\\u{code:04x}"


def clean_text(text: str) -> str:
    """``text`` made encodable: every lone surrogate escaped visibly, the rest unchanged.

    A byte that is not UTF-8 (kept by Python as U+DC80..U+DCFF) becomes ``\\xNN``, the escaped
    form of such names in every output; any other lone surrogate becomes ``\\uNNNN``.

    >>> clean_text("bad\\udce9name"), clean_text("x\\ud800y"), clean_text("Zoë")
    ('bad\\\\xe9name', 'x\\\\ud800y', 'Zoë')
    """
    return _SURROGATE.sub(_escape_surrogate, text) if _SURROGATE.search(text) else text


def visible_text(text: str) -> str:
    """One line of ``text`` as shown on a terminal: :func:`clean_text`, then every character
    that is not printable but a space (controls: ESC starting a sequence that sets the window
    title, clears the screen or hides text; a carriage return; a line break; bidirectional
    overrides) escaped as ``\\x1b``, ``\\r``, ``\\u202e``: such text can neither act on the
    terminal nor hide what follows.

    >>> print(visible_text("ana\\x1b]0;owned\\x07 \\x1b[2J\\rZoë\\u202e\\nx"))
    ana\\x1b]0;owned\\x07 \\x1b[2J\\rZoë\\u202e\\nx
    """
    text = clean_text(text)
    if text.isprintable():
        return text
    return "".join(c if c.isprintable() or c == " " else c.encode("unicode_escape").decode()
                   for c in text)


def clean_data(value):
    """:func:`clean_text` applied to every string (keys too) of a JSON-like value.

    >>> clean_data({"id": "b\\udce9", "n": [1, "\\ud800"]})
    {'id': 'b\\\\xe9', 'n': [1, '\\\\ud800']}
    """
    if isinstance(value, str):
        return clean_text(value)
    if isinstance(value, dict):
        return {clean_data(k): clean_data(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [clean_data(v) for v in value]
    return value


def write_text(path: str | os.PathLike, text: str, *, encoding: str = "utf-8") -> None:
    """Write ``text`` (cleaned, newlines as given) to ``path`` atomically.

    A reader never sees a half-written file and a failed write leaves the old file intact.
    Raises :class:`~mechgrade.errors.OutputError`.

    The file is not fsynced: ``os.replace`` of a complete temporary file already gives readers
    and a crashed or killed process all-or-nothing files; only a power cut or a kernel crash
    could leave a file empty, and every output can be written again by re-running mechgrade
    (runs are reproducible byte for byte). An fsync per file made writing a class's feedback
    take seconds. A file that already holds exactly ``text`` is left as it is.

    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "f.txt"
    >>> write_text(p, "bad\\udce9name\\n"); p.read_text()
    'bad\\\\xe9name\\n'
    """
    write_bytes(path, clean_text(text).encode(encoding))


def write_bytes(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically, as :func:`write_text` writes text.

    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "f.zip"
    >>> write_bytes(p, b"PK"); p.read_bytes()
    b'PK'
    """
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    if _holds(target, data) or _link_earlier(target, data):
        return
    try:
        temp_name = _write_temporary(folder, target.name, data)
        try:
            os.replace(temp_name, target)
        except BaseException:
            Path(temp_name).unlink(missing_ok=True)
            raise
    except OSError as err:
        if not folder.is_dir():
            raise OutputError(f"expected an existing folder to write {target.name!r} into, "
                              f"found none", where=Location(str(folder))) from None
        if target.is_dir():
            raise OutputError("expected a file path to write, found a folder",
                              where=Location(str(target))) from None
        raise OutputError(f"cannot write the file ({err.strerror or err})",
                          where=Location(str(target))) from None


def _holds(target: Path, data: bytes) -> bool:
    """Whether ``target`` is a regular file holding exactly ``data`` already.

    A re-run writes mostly the same files again; leaving those alone is much faster than
    replacing them (replacing a file makes the file system flush and free the old one) and
    just as correct. Opened without blocking, so a named pipe in the way is never waited on.
    """
    try:
        fd = os.open(target, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError:
        return False
    try:
        with os.fdopen(fd, "rb") as handle:
            info = os.fstat(handle.fileno())
            if not stat.S_ISREG(info.st_mode) or info.st_size != len(data):
                return False
            return handle.read(len(data) + 1) == data
    except OSError:
        return False


_EARLIER: list[tuple[str, Path]] = []


@contextmanager
def replacing(new: str | os.PathLike, old: str | os.PathLike) -> Iterator[None]:
    """While in this context, a file written into folder ``new`` that ``old`` holds already,
    at the same place and byte for byte, is made a hard link to it instead.

    For an output folder built beside the one it replaces (:mod:`mechgrade.outfolder`): a
    regrade writes mostly the same pages again, and linking is much faster than writing a new
    file and then deleting the old one.
    """
    _EARLIER.append((os.path.join(new, ""), Path(old)))
    try:
        yield
    finally:
        _EARLIER.pop()


def _link_earlier(target: Path, data: bytes) -> bool:
    """Whether ``target`` was made a link to the same file of the folder being replaced."""
    for prefix, old in _EARLIER:
        name = str(target)
        if name.startswith(prefix):
            earlier = old / name[len(prefix):]
            if _holds(earlier, data):
                try:
                    os.link(earlier, target)
                    return True
                except OSError:
                    return False
    return False


_temporary_names = itertools.count()


def _write_temporary(folder: Path, name: str, data: bytes) -> str:
    """A new file next to ``name`` in ``folder`` holding ``data``, with the mode ``open()``
    gives new files (the umask applies), never one that existed before."""
    for _ in range(100):
        temp_name = os.path.join(folder, f".{name}.{os.getpid()}.{next(_temporary_names)}.tmp")
        try:
            fd = os.open(temp_name, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        except FileExistsError:
            continue
        try:
            with os.fdopen(fd, "wb") as handle:
                handle.write(data)
        except BaseException:
            Path(temp_name).unlink(missing_ok=True)
            raise
        return temp_name
    raise FileExistsError(errno.EEXIST, "no free temporary file name")


def write_json(path: str | os.PathLike, data: object) -> None:
    """Write a JSON document atomically: UTF-8, not ASCII-escaped, indented, final newline.

    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "r.json"
    >>> write_json(p, {"id": "b\\udce9"}); json.loads(p.read_text())
    {'id': 'b\\\\xe9'}
    """
    try:
        text = json_text(data)
    except OutputError as err:
        raise err.located(Location(str(path))) from None
    write_text(path, text)


def json_text(data: object) -> str:
    """The text :func:`write_json` writes for ``data`` (strings cleaned by :func:`clean_data`).

    >>> json_text({"n": [1, "x"]})
    '{\\n  "n": [\\n    1,\\n    "x"\\n  ]\\n}\\n'
    """
    try:
        text = json.dumps(data, ensure_ascii=False, indent=2, allow_nan=False)
        if _SURROGATE.search(text):  # rare: clean every string, then write it again
            text = json.dumps(clean_data(data), ensure_ascii=False, indent=2, allow_nan=False)
    except ValueError as err:  # NaN or infinity: not JSON, and a sign of a bug upstream
        raise OutputError(f"expected finite numbers to write as JSON, found {err}") from None
    return text + "\n"


_UNSAFE = re.compile(r"[^A-Za-z0-9._-]+")
_WINDOWS_DEVICES = {"CON", "PRN", "AUX", "NUL", *(f"COM{i}" for i in range(10)),
                    *(f"LPT{i}" for i in range(10))}


def safe_file_names(ids: list[str]) -> list[str]:
    """A safe, distinct file name (without suffix) for every id, in order.

    ASCII letters, digits and ``._-`` only, at most 80 characters, never starting with ``-``
    (read as an option by shell tools) or ``.``, no Windows device names; ids that would
    collide (also in letter case, for case-insensitive file systems) get ``-2``, ``-3``...

    >>> safe_file_names(["ana", "../x", "Ana", "é b", "-rf", "nul", "bad\\\\xe9", "x" * 300])[:7]
    ['ana', 'x', 'Ana-2', 'e_b', 'rf', 'student_nul', 'bad_xe9']
    """
    names: list[str] = []
    used: set[str] = set()
    for ident in ids:
        ascii_id = unicodedata.normalize("NFKD", ident).encode("ascii", "ignore").decode()
        base = _UNSAFE.sub("_", ascii_id).lstrip("-._").rstrip("._")[:80] or "student"
        if base.split(".")[0].upper() in _WINDOWS_DEVICES:
            base = f"student_{base}"
        name, n = base, 1
        while name.casefold() in used:
            n += 1
            name = f"{base}-{n}"
        used.add(name.casefold())
        names.append(name)
    return names
