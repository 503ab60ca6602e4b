"""Grade every typical mistake of the tables beside this file and count how it was diagnosed.

Run: python tests/data/mistakes/measure.py [-v]   (with the mechgrade to measure importable)
Classes: ``named`` (a code the table lists), ``generic`` (a whole-answer diagnosis true of it
that does not name it: the row's ``generic`` codes), ``none`` (judged wrong, no diagnosis),
``correct`` (judged right: the mistake is inside the tolerance), ``wrong`` (another diagnosis).
Counted for the kinematics problems, the dynamics problems (bodies and loads) and the whole
library.
A mistake the problem's author declared is named in the author's words (code ``mistake``).
"""
from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

import yaml

from mechgrade.grade import diagnose
from mechgrade.grade.compare import assess
from mechgrade.grade.policy import GradingPolicy
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.spec import load_problem
from mechgrade.units import from_si, to_si

HERE = Path(__file__).parent


def code_of(label: str | None, result) -> str | None:
    """The diagnosis code behind an assessment's label."""
    if label is None:
        return None
    if any(m.message == label for m in result.mistakes):
        return "mistake"
    codes = {lab: code for code, lab, *_ in diagnose._FACTORS}
    codes.update({v: k for k, v in getattr(diagnose, "LABELS", {}).items()})
    codes.update({"swapped components": "swapped", "wrong direction": "direction",
                  "wrong magnitude": "magnitude", "wrong dimension": "dimension"})
    return codes.get(label, label)


def codes_of(label: str | None, result) -> list[str]:
    """The codes behind a label that may name two families that fit equally ("X or Y"): a
    label of its own wins over a split (one label has " or " in its words)."""
    if label is None:
        return []
    whole = code_of(label, result)
    if whole != label:
        return [whole]
    parts = label.split(" or ")
    for i in range(1, len(parts)):
        first, second = " or ".join(parts[:i]), " or ".join(parts[i:])
        codes = [code_of(first, result), code_of(second, result)]
        if codes != [first, second]:
            return codes
    return [label]


def classify(row: dict, result, policy: GradingPolicy = GradingPolicy()) -> tuple[str, object]:
    """A row's class; a diagnosis naming two families is named when either is the row's."""
    judged = assess(row["answer"], result, policy)
    if judged.verdict == "correct":
        return "correct", judged
    codes = codes_of(judged.diagnosis, result)
    if not codes:
        return "none", judged
    # the author's declared mistakes name theirs in the author's words
    if any(code in row["diagnosis"] or code == "mistake" for code in codes):
        return "named", judged
    if all(code in row.get("generic", ()) for code in codes):
        return "generic", judged
    return "wrong", judged


def rows():
    """``(problem id, group, row, result)`` for every row of every table."""
    for path in sorted(HERE.glob("*.yaml")):
        problem = load_problem(shipped_dir("problems") / path.name)
        group = "kinematics" if problem.dynamics is None else "dynamics"
        solution = solve(problem)
        for row in yaml.safe_load(path.read_text(encoding="utf-8")):
            yield path.stem, group, row, solution.result(row["objective"])


def notations(result):
    """Correct answers as the docs allow: 3 s.f., another unit of the same kind, and for
    vectors the i/j form."""
    unit = result.unit
    other = {"ft/s^2": "m/s^2", "m/s^2": "ft/s^2", "ft/s": "m/s", "m/s": "km/h",
             "in/s": "cm/s", "cm/s": "m/s", "mm/s^2": "m/s^2", "m": "cm", "ft": "in",
             "deg": "rad", "rad/s": "deg/s", "rad/s^2": "deg/s^2", "N": "kN", "J": "kJ",
             "s": "ms", "W": "kW", "N*s": "kN*s"}.get(unit)
    values = result.value if result.kind == "vector" else (result.value,)

    def three(v):
        return "0" if abs(v) < 1e-9 else f"{v:.3g}"
    u = f" {unit}" if unit not in ("", "1") else ""
    if result.kind == "vector":
        yield "(" + ", ".join(three(v) for v in values) + ")" + u
        terms = [f"{three(v)} {axis}" for v, axis in zip(values, "ijk") if abs(v) > 1e-9]
        if terms and unit not in ("", "1"):
            yield "(" + " + ".join(terms).replace("+ -", "- ") + ")" + u
        if other:
            converted = [from_si(to_si(v, unit), other) for v in values]
            yield "(" + ", ".join(f"{v:.4g}" if abs(v) > 1e-9 else "0"
                                  for v in converted) + f") {other}"
    else:
        yield three(values[0]) + u
        if other:
            yield f"{from_si(to_si(values[0], unit), other):.4g} {other}"


def rate(counts: Counter) -> str:
    total = sum(counts.values())
    return ", ".join(f"{k} {counts[k]} ({100 * counts[k] / total:.0f} %)"
                     for k in ("named", "generic", "none", "correct", "wrong")) + f" of {total}"


if __name__ == "__main__":
    counts = {"kinematics": Counter(), "dynamics": Counter()}
    for problem, group, row, result in rows():
        kind, judged = classify(row, result)
        counts[group][kind] += 1
        if "-v" in sys.argv or kind != "named":
            print(f"{kind:8} {problem}.{row['objective']}: {row['mistake']} -> "
                  f"{judged.diagnosis!r}: {judged.feedback}")
    for group, counted in counts.items():
        print(f"{group}: {rate(counted)}")
    print(f"library: {rate(counts['kinematics'] + counts['dynamics'])}")
