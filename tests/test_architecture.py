"""Imports point one way: spec -> mechanics -> solve -> grade -> report/export -> cli; no cycles."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "mechgrade"
# Each layer may import only from itself and the layers listed before it.
ORDER = ["base", "spec", "mechanics", "solve", "check", "grade", "export", "report", "cli"]
BASE = {"errors", "units", "yamlio", "jsonio", "files", "resources", "expressions", "roster",
        "schema_errors", "tolerance", "parallel", "__init__", "__main__"}


def layer(module: str) -> str:
    """The layer of a module named relative to mechgrade (``export.canvas``; ``""`` is the
    package itself)."""
    top = module.split(".")[0] or "__init__"
    return "base" if top in BASE else top


def modules() -> dict[str, Path]:
    """Every module by its name relative to mechgrade (a package by its own name)."""
    out = {}
    for path in sorted(SRC.rglob("*.py")):
        parts = path.relative_to(SRC).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


MODULES = modules()


def imports(name: str, path: Path, known: dict[str, Path] = MODULES):
    """The modules ``name`` imports: external ones by their name, mechgrade's own as
    ``mechgrade.<module>``. ``from P import x`` is resolved to the module or package ``P.x``
    when there is one (``from . import files``, ``from mechgrade import roster``)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
    package = [p for p in package if p]
    # Imports under "if TYPE_CHECKING:" never run: they name types for annotations only.
    type_only = {id(inner) for node in ast.walk(tree) if isinstance(node, ast.If)
                 and getattr(node.test, "id", None) == "TYPE_CHECKING"
                 for inner in ast.walk(node)}
    for node in ast.walk(tree):
        if id(node) in type_only:
            continue
        if isinstance(node, ast.Import):
            yield from (alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - node.level + 1]
                inner = ".".join(base + ([node.module] if node.module else []))
                target = f"mechgrade.{inner}" if inner else "mechgrade"
            else:
                target = node.module or ""
            for alias in node.names:
                candidate = f"{target}.{alias.name}"
                if candidate.startswith("mechgrade.") and \
                        candidate[len("mechgrade."):] in known:
                    yield candidate
                else:
                    yield target


def own(target: str) -> str | None:
    """A mechgrade module's name relative to mechgrade, or ``None`` for another library."""
    if target == "mechgrade":
        return ""
    return target[len("mechgrade."):] if target.startswith("mechgrade.") else None


@pytest.mark.parametrize("name, path", list(MODULES.items()), ids=list(MODULES))
def test_module_imports_only_earlier_layers(name, path):
    mine = ORDER.index(layer(name))
    for target in imports(name, path):
        if target.startswith("sympy.physics"):
            assert layer(name) == "mechanics", f"{name} imports {target}"
        if target.startswith("sympy"):
            assert layer(name) not in ("report", "export"), f"{name} imports {target}"
        other = own(target)
        if other is None or name == "__main__":
            continue
        assert ORDER.index(layer(other)) <= mine, f"{name} imports {target}"


def import_graph(known: dict[str, Path] = MODULES) -> dict[str, set[str]]:
    graph = {}
    for name, path in known.items():
        targets = {own(t) for t in imports(name, path, known)}
        graph[name] = {t for t in targets if t is not None and t in known and t != name}
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The import cycles of ``graph``: its strongly connected components of two or more
    modules (Tarjan's algorithm), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for nxt in sorted(graph.get(node, ())):
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                top = stack.pop()
                on_stack.discard(top)
                component.append(top)
                if top == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def test_no_module_imports_itself_through_others():
    assert cycles(import_graph()) == []


# --- the checks themselves ---------------------------------------------------------------------

def fake_modules(tmp_path: Path, files: dict[str, str]) -> dict[str, Path]:
    known = {}
    for name, text in files.items():
        parts = name.split(".") if name else []
        is_package = name == "" or name in {f.rsplit(".", 1)[0] for f in files if "." in f}
        path = tmp_path.joinpath(*parts, "__init__.py") if is_package else \
            tmp_path.joinpath(*parts[:-1], parts[-1] + ".py")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        known[name] = path
    return known


@pytest.mark.parametrize("importer, text, target", [
    ("grade.run", "from .. import report\n", "mechgrade.report"),
    ("grade.run", "from . import sandbox\n", "mechgrade.grade.sandbox"),
    ("grade.run", "from mechgrade import report\n", "mechgrade.report"),
    ("grade.run", "from .. import __version__\n", "mechgrade"),
    ("grade", "from . import run\n", "mechgrade.grade.run"),
    ("grade.run", "from ..report.class_report import x\n", "mechgrade.report.class_report"),
])
def test_from_imports_resolve_to_the_module_they_name(tmp_path, importer, text, target):
    known = fake_modules(tmp_path, {"": "", "grade": "", "grade.run": "", "grade.sandbox": "",
                                    "report": "", "report.class_report": ""})
    known[importer].write_text(text, encoding="utf-8")
    assert list(imports(importer, known[importer], known)) == [target]


def test_an_upward_from_import_is_a_layer_violation():
    # What test_module_imports_only_earlier_layers asserts for "from .. import report" in grade.
    assert ORDER.index(layer(own("mechgrade.report"))) > ORDER.index(layer("grade.run"))


def test_a_cycle_through_three_modules_is_found(tmp_path):
    known = fake_modules(tmp_path, {"": "", "a": "from . import b\n", "b": "from .c import x\n",
                                    "c": "import mechgrade.a\n", "d": "from . import a\n"})
    assert cycles(import_graph(known)) == [["a", "b", "c"]]
