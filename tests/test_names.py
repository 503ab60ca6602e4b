"""One meaning per name for the types issue 24 found named twice: the grading plan is ``Plan``
(the solver's are ``KinematicsPlan``, ``KineticsPlan``, ``AnalysisPlan``), a ``branch:`` entry
is ``Branch``, a solve's result or error is ``Outcome``, and the grading policy is
``GradingPolicy`` (no ``Policy`` or ``compare_policy`` beside it)."""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "mechgrade"
ONCE = ("Plan", "Branch", "Outcome", "GradingPolicy")
NEVER = ("Policy", "compare_policy")


def defined(text: str) -> list[str]:
    """The names a module's top level defines: classes, functions and assigned names (type
    aliases among them).

    >>> defined("class A: pass\\nB = int | None\\ndef f(): pass\\nC: int = 1\\nif x:\\n    D = 1\\n")
    ['A', 'B', 'f', 'C']
    """
    out = []
    for node in ast.parse(text).body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            out.append(node.name)
        elif isinstance(node, ast.Assign):
            out += [t.id for t in node.targets if isinstance(t, ast.Name)]
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            out.append(node.target.id)
    return out


def test_each_of_the_names_issue_24_made_one_is_defined_once():
    where: dict[str, list[str]] = {}
    for path in sorted(SRC.rglob("*.py")):
        for name in defined(path.read_text(encoding="utf-8")):
            if name in ONCE + NEVER:
                where.setdefault(name, []).append(str(path.relative_to(SRC)))
    assert {name: places for name, places in where.items()
            if len(places) > 1 or name in NEVER} == {}
