"""Every rule switched off for one line says why: ``# noqa: CODE - the reason`` (the lint gate's
ignores in pyproject.toml say why next to each). A statement written over several lines may
give the reason once, on its first line that needs it: the lines after it switching off the
same rules carry that reason on."""

from __future__ import annotations

import io
import re
import tokenize
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
NOQA = re.compile(r"#\s*noqa\b(?::\s*(?P<codes>[A-Z]+[0-9]*(?:\s*,\s*[A-Z]+[0-9]*)*))?"
                  r"(?P<rest>.*)$")
REASON = re.compile(r"^\s*-+\s*\S")


def unexplained(text: str) -> list[int]:
    """The lines of ``text`` (Python source) whose ``noqa`` gives no reason of its own or of
    the line just above it for the same rules.

    >>> unexplained("x = 1  # noqa: E731 - a named lambda\\ny = 2  # noqa: E731\\n")
    []
    >>> unexplained("x = 1  # noqa: E731\\n\\ny = 2  # noqa: B023 - why\\nz = 3  # noqa\\n")
    [1, 4]
    """
    found: list[int] = []
    reasons: dict[int, frozenset[str]] = {}  # line: the rules a reason on it covers
    for token in tokenize.generate_tokens(io.StringIO(text).readline):
        match = NOQA.search(token.string) if token.type == tokenize.COMMENT else None
        if match is None:
            continue
        line = token.start[0]
        codes = frozenset(re.split(r"\s*,\s*", match["codes"])) if match["codes"] else None
        if REASON.match(match["rest"]) and codes is not None:
            reasons[line] = codes
        elif codes is None or not codes <= reasons.get(line - 1, frozenset()):
            found.append(line)
        else:
            reasons[line] = codes
    return found


def test_every_noqa_says_why():
    files = sorted(p for folder in ("src", "tests", "bench") for p in (ROOT / folder).rglob("*.py"))
    found = {str(p.relative_to(ROOT)): unexplained(p.read_text(encoding="utf-8")) for p in files}
    assert {path: lines for path, lines in found.items() if lines} == {}
