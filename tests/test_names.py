"""One meaning per name for the types issue 24 found named twice: the grading plan is ``Plan``
(the solver's are ``KinematicsPlan``, ``KineticsPlan``, ``AnalysisPlan``), a ``branch:`` entry
is ``Branch``, a solve's result or error is ``Outcome``, and the grading policy is
``GradingPolicy`` (no ``Policy`` or ``compare_policy`` beside it); a friction bound is
``FrictionBound`` (a declared range ``Limits``), a catalogue's filing ``Approach`` (a spec's
analysis ``Analysis``), a root of the levels ``Candidate`` (an upload's file ``AnswerFile``), a
step of the worked solution ``WorkedStep`` (a group's solving ``GroupStep``) and a page point
``Point2``; the bare ``Bound`` and ``Step`` said neither, and are not names."""

from __future__ import annotations

import ast
from functools import lru_cache
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "mechgrade"
ONCE = ("Plan", "Branch", "Outcome", "GradingPolicy", "Analysis", "FrictionBound", "Candidate",
        "Point2", "GroupStep")
NEVER = ("Policy", "compare_policy", "Bound", "Step")


@lru_cache(maxsize=None)
def _parsed(text: str) -> ast.Module:
    """A module's tree, parsed once for every check of this file."""
    return ast.parse(text)


def defined(text: str) -> list[str]:
    """The names a module's top level defines: classes, functions and assigned names (type
    aliases among them).

    >>> defined("class A: pass\\nB = int | None\\ndef f(): pass\\nC: int = 1\\nif x:\\n    D = 1\\n")
    ['A', 'B', 'f', 'C']
    """
    out = []
    for node in _parsed(text).body:
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


# Where a kind is text on purpose: the edge that reads it into its type (a spec's YAML keys)
# and jsonschema's own names for its checks.
TEXT_AT_THE_EDGE = {("spec/dynamics.py", "_analysis"), ("spec/dynamics.py", "_part"),
                    ("schema_errors.py", "_explain"), ("schema_errors.py", "_message")}


def kinds_compared_with_text(text: str) -> list[tuple[str, int]]:
    """The ``(function, line)`` where a kind (a field ``.kind`` or ``.format``, a name
    ``kind``, ``status`` or ``verdict``) is compared with a text, or a tuple of texts, instead
    of with its type's members.

    >>> kinds_compared_with_text("r.kind == 'vector'\\nr.kind in ('a', 'b')\\n"
    ...                          "r.kind is K.VECTOR\\ndef f(kind):\\n    return kind == 'ok'\\n")
    [('', 1), ('', 2), ('f', 5)]
    """
    def field(node: ast.expr) -> bool:
        return (isinstance(node, ast.Attribute) and node.attr in ("kind", "format")) \
            or (isinstance(node, ast.Name) and node.id in KINDS)

    def texts(node: ast.expr) -> bool:
        items = node.elts if isinstance(node, (ast.Tuple, ast.List, ast.Set)) else [node]
        return bool(items) and all(isinstance(i, ast.Constant) and isinstance(i.value, str)
                                   for i in items)

    tree = _parsed(text)
    owner = {id(inner): node.name for node in ast.walk(tree)
             if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
             for inner in ast.walk(node)}
    return sorted((owner.get(id(node), ""), node.lineno) for node in ast.walk(tree)
                  if isinstance(node, ast.Compare)
                  and any((field(a) and texts(b)) or (field(b) and texts(a))
                          for a, b in zip([node.left, *node.comparators], node.comparators)))


def test_a_kind_is_compared_with_its_types_members_not_with_text():
    found = {(str(path.relative_to(SRC)), function, line) for path in sorted(SRC.rglob("*.py"))
             for function, line in kinds_compared_with_text(path.read_text(encoding="utf-8"))}
    assert {f for f in found if f[:2] not in TEXT_AT_THE_EDGE} == set()


KINDS = {"status", "verdict", "kind"}


def kinds_held_as_text(text: str) -> list[tuple[str, str]]:
    """The ``(class, field)`` of every class field named ``status``, ``verdict`` or ``kind``
    annotated as a text.

    >>> kinds_held_as_text("class A:\\n    status: str\\n    kind: Kind\\n    verdict: str | None\\n")
    [('A', 'status'), ('A', 'verdict')]
    """
    return [(node.name, item.target.id) for node in ast.walk(_parsed(text))
            if isinstance(node, ast.ClassDef) for item in node.body
            if isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name)
            and item.target.id in KINDS
            and any(isinstance(n, ast.Name) and n.id == "str" for n in ast.walk(item.annotation))]


def test_a_status_verdict_or_kind_field_is_of_its_kinds_type():
    found = [(str(path.relative_to(SRC)), *held) for path in sorted(SRC.rglob("*.py"))
             for held in kinds_held_as_text(path.read_text(encoding="utf-8"))]
    assert found == []


def kind_parameters_of_text(text: str) -> list[str]:
    """The functions with a parameter named ``kind`` annotated as a text.

    >>> kind_parameters_of_text("def f(kind: str): pass\\ndef g(kind: Kind): pass\\n")
    ['f']
    """
    return [node.name for node in ast.walk(_parsed(text))
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
            for arg in (*node.args.posonlyargs, *node.args.args, *node.args.kwonlyargs)
            if arg.arg == "kind" and arg.annotation is not None
            and any(isinstance(n, ast.Name) and n.id == "str" for n in ast.walk(arg.annotation))]


def test_a_kind_parameter_is_of_its_kinds_type():
    found = {str(path.relative_to(SRC)): names for path in sorted(SRC.rglob("*.py"))
             if (names := kind_parameters_of_text(path.read_text(encoding="utf-8")))}
    assert found == {}
