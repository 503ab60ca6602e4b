"""Reading a user's text file with one clear message for every way it can fail.

>>> from mechgrade.errors import SpecError
>>> read_text("no/such/file.yaml", what="a problem file", error=SpecError)
Traceback (most recent call last):
...
mechgrade.errors.SpecError: no/such/file.yaml: expected a problem file, found no such file
"""

from __future__ import annotations

from pathlib import Path

from .errors import Location, MechgradeError

MAX_BYTES = 1_000_000


def read_text(path: str | Path, *, what: str, error: type[MechgradeError],
              max_bytes: int = MAX_BYTES, hint: str = "") -> str:
    """The UTF-8 text (BOM allowed) of ``path``, or ``error`` saying what was found instead.

    ``what`` names the expected file ("a roster CSV file"); ``hint`` is added to the encoding
    message (for example how to save a spreadsheet as UTF-8).
    """
    name = str(path)
    path = Path(path)
    try:
        size = path.stat().st_size
        if path.is_dir():
            raise error(f"expected {what}, found a folder", where=Location(name))
        if size > max_bytes:
            raise error(f"expected {what} of at most {max_bytes} bytes, found {size} bytes",
                        where=Location(name))
        data = path.read_bytes()
    except FileNotFoundError:
        raise error(f"expected {what}, found no such file", where=Location(name)) from None
    except OSError as exc:
        raise error(f"cannot read the file ({exc.strerror or exc})", where=Location(name)) \
            from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise error(f"expected UTF-8 text{hint}, found byte 0x{data[exc.start]:02x}, which is "
                    "not UTF-8", where=Location(name, line)) from None
