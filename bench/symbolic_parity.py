"""Verdicts before and after a change to symbolic judging: every answer's whole assessment.

Answers to the four symbolic objectives of ``bench/symbolic.py``: its forms, each changed by
up to two typical slips drawn at random (a sign, a factor of 2, g, π or 180/π, sin for cos, a
power, a term added, a wrong dimension, Greek letters, a glued divisor, text cut short...), and
as many of ``bench/answer_fuzz.py``'s texts. Run once on each tree, then compare:

    PYTHONPATH=OLD/src python bench/symbolic_parity.py old.json
    PYTHONPATH=src python bench/symbolic_parity.py new.json
    python bench/symbolic_parity.py --compare old.json new.json

(the first line printed names the tree that judged).
"""

from __future__ import annotations

import json
import random
import sys
from pathlib import Path

SLIPS = (
    lambda t: f"2*({t})", lambda t: f"-({t})", lambda t: f"({t})/2",
    lambda t: t.replace("sin", "cos"), lambda t: t.replace("+", "-"), lambda t: f"({t})*9.81",
    lambda t: f"({t})*180/pi", lambda t: f"({t}) + L", lambda t: f"({t})^2",
    lambda t: f"3({t})/2L", lambda t: f"sqrt({t})", lambda t: f"({t})*pi",
    lambda t: t.replace("^2", "^3"), lambda t: t.replace("thetad", "θ̇"),
    lambda t: t + " + 1e-5", lambda t: f"({t})*100", lambda t: t.replace("*", " "),
    lambda t: t[:-1], lambda t: f"({t}) m/s", lambda t: f"1/({t})", lambda t: f"({t}) + xd",
    lambda t: f"{t}+{t}", lambda t: f"e^({t})", lambda t: f"({t})/(2g)")


def answers(count: int) -> list[tuple[tuple[str, str], str]]:
    from answer_fuzz import PIECES
    from symbolic import FORMS

    rng, fuzz = random.Random(24), random.Random(7)
    keys = list(FORMS)
    out = []
    for _ in range(count):
        key = rng.choice(keys)
        text = rng.choice(FORMS[key])[0]
        for _ in range(rng.randint(0, 2)):
            text = rng.choice(SLIPS)(text)
        out.append((key, text))
    out += [(fuzz.choice(keys), "".join(fuzz.choice(PIECES) for _ in range(fuzz.randint(1, 4))))
            for _ in range(count // 2)]
    return out


def judge(path: str, count: int = 4000) -> None:
    import mechgrade
    from mechgrade.grade.compare import assess
    from mechgrade.grade.policy import GradingPolicy
    from symbolic import references

    print(f"judged by {mechgrade.__file__}")
    refs, policy = references(), GradingPolicy()
    verdicts = [repr(assess(text, refs[key], policy)) for key, text in answers(count)]
    Path(path).write_text(json.dumps(verdicts), encoding="utf-8")
    print(f"{len(verdicts)} answers judged")


def compare(old: str, new: str) -> None:
    a, b = (json.loads(Path(p).read_text(encoding="utf-8")) for p in (old, new))
    differ = [i for i, (x, y) in enumerate(zip(a, b)) if x != y]
    print(f"{len(differ)} of {len(a)} assessments differ" + ("" if len(a) == len(b) else
                                                            f" (and {len(b)} against {len(a)})"))
    for i in differ[:5]:
        print(f"  {a[i]}\n  {b[i]}")


if __name__ == "__main__":
    if sys.argv[1] == "--compare":
        compare(sys.argv[2], sys.argv[3])
    else:
        judge(sys.argv[1])
