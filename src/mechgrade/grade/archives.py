"""Zip files someone else made, read in memory under the rules the folder reader keeps.

A zip is never extracted: member names never become paths of their own. A member is refused,
with the reason, when its name is absolute or climbs out (``..``), when it is a link, when it
is encrypted, when two members share its name (which one is the student's cannot be told), or
when it declares an expansion no answers file has (a zip bomb); every read is bounded
(:func:`read_member`), so a member whose header lies about its size is cut short all the
same. A name the zip stores without the UTF-8 flag is read as UTF-8 when it is, else as the
historical code page the format prescribes (cp437).

>>> import io, zipfile
>>> data = io.BytesIO()
>>> with zipfile.ZipFile(data, "w") as z:
...     z.writestr("ok/answers.txt", "p.v = 1 m/s")
...     z.writestr("../escape.txt", "x")
>>> members, refused = safe_members(zipfile.ZipFile(data))
>>> [m.name for m in members], refused
(['ok/answers.txt'], [('../escape.txt', 'its name climbs out of the zip (..); it was not read')])
"""

from __future__ import annotations

import stat
import zipfile
import zlib
from collections import Counter
from dataclasses import dataclass
from pathlib import PurePosixPath

from ..files import clean_text

MAX_RATIO = 200
"""A member declaring more than this many bytes out per byte in, above :data:`RATIO_FLOOR`, is
refused as a zip bomb (text compresses about 5 to 20 times; deflate's limit is about 1000)."""
RATIO_FLOOR = 1_000_000


@dataclass(frozen=True)
class Member:
    """A file member: its name as shown (decoded, cleaned), and the zip's entry for it."""

    name: str
    info: zipfile.ZipInfo


def member_name(info: zipfile.ZipInfo) -> str:
    """The member's name as its maker meant it: UTF-8 when the bytes are UTF-8 (many tools
    write UTF-8 without the flag), else cp437 as zipfile decoded it; backslashes as ``/``.

    >>> info = zipfile.ZipInfo("caf\\u00e9.txt".encode().decode("cp437"))
    >>> member_name(info)
    'café.txt'
    """
    name = info.filename
    if not info.flag_bits & 0x800:
        try:
            name = name.encode("cp437").decode("utf-8")
        except (UnicodeEncodeError, UnicodeDecodeError):
            pass
    return clean_text(name.replace("\\", "/"))


def member_problem(info: zipfile.ZipInfo, name: str) -> str | None:
    """Why a member must not be read (see the module doc), or ``None``."""
    parts = PurePosixPath(name).parts
    if name.startswith("/") or (len(name) > 1 and name[1] == ":"):
        return "its name is an absolute path; it was not read"
    if ".." in parts:
        return "its name climbs out of the zip (..); it was not read"
    if stat.S_ISLNK(info.external_attr >> 16):
        return "is a link; links in a zip are never followed"
    if info.flag_bits & 0x1:
        return "is encrypted; it was not read"
    if info.file_size > RATIO_FLOOR and info.file_size > MAX_RATIO * max(info.compress_size, 1):
        return (f"declares {info.file_size} bytes from {info.compress_size} (a zip bomb); "
                "it was not read")
    return None


def safe_members(archive: zipfile.ZipFile) -> tuple[list[Member], list[tuple[str, str]]]:
    """The file members that may be read, and ``(name, reason)`` for each refused one
    (folders are neither)."""
    infos = [(member_name(info), info) for info in archive.infolist() if not info.is_dir()]
    counts = Counter(name for name, _ in infos)
    members, refused = [], []
    for name, info in infos:
        problem = member_problem(info, name)
        if problem is None and counts[name] > 1:
            problem = (f"the zip holds {counts[name]} members of this name: none was read "
                       "(which one is meant cannot be told)")
        if problem is None:
            members.append(Member(name, info))
        else:
            refused.append((name, problem))
    return members, refused


def read_member(archive: zipfile.ZipFile, member: Member, limit: int) -> bytes | str:
    """At most ``limit`` + 1 bytes of ``member`` (more than ``limit`` means too large), or the
    reason it cannot be read."""
    try:
        with archive.open(member.info) as handle:
            return handle.read(limit + 1)
    except (OSError, zipfile.BadZipFile, RuntimeError, ValueError, NotImplementedError,
            EOFError, zlib.error) as exc:
        return f"cannot be read ({type(exc).__name__})"
