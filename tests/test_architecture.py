"""Imports point one way: spec -> mechanics -> solve -> grade -> report/export -> cli; no cycles.

Inside the base layer too there is an order (:data:`BASE_ORDER`); only ``mechanics`` imports
``sympy.physics``; ``report`` and ``export`` import no sympy at all; an import under
``if TYPE_CHECKING:`` is for annotations only (its ``else:`` branch runs, so it counts); and a
module found by name at run time (``importlib.import_module``, ``__import__``) escapes all of
this, so only :data:`DYNAMIC_IMPORTERS` may do it (each looks up a registry of its own layer).
``StrEnum`` comes from :data:`STR_ENUM_HOME` alone (Python 3.10's :mod:`enum` has none).
"""

from __future__ import annotations

import ast
import shutil
from functools import lru_cache
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "mechgrade"
# Each layer may import only from itself and the layers listed before it.
ORDER = ["base", "spec", "mechanics", "solve", "check", "grade", "export", "report", "cli"]
BASE = {"errors", "units", "yamlio", "jsonio", "files", "outfolder", "resources", "expressions",
        "roster", "codec", "schema_errors", "tolerance", "parallel", "__init__", "__main__"}
# The base layer's own order: a base module imports only base modules listed before it (or its
# own package's modules, whose cycles test_no_module_imports_itself_through_others catches).
BASE_ORDER = ["", "errors", "codec", "resources", "tolerance", "schema_errors", "files", "jsonio",
              "parallel", "outfolder", "yamlio", "roster", "expressions.excerpt", "units",
              "expressions", "__main__"]
# The only modules that import a module named at run time: the exporter registry and the CLI's
# lazily loaded commands, each naming modules of its own package.
DYNAMIC_IMPORTERS = {"export", "cli.common"}


def layer(module: str) -> str:
    """The layer of a module named relative to mechgrade (``export.canvas``; ``""`` is the
    package itself)."""
    top = module.split(".")[0] or "__init__"
    return "base" if top in BASE else top


def base_rank(module: str) -> int:
    """A base module's place in :data:`BASE_ORDER` (its longest listed prefix)."""
    matches = [i for i, entry in enumerate(BASE_ORDER)
               if module == entry or (entry and module.startswith(entry + "."))]
    return max(matches, key=lambda i: len(BASE_ORDER[i]))


def modules(root: Path = SRC) -> dict[str, Path]:
    """Every module under ``root`` (mechgrade's package folder) by its name relative to
    mechgrade (a package by its own name)."""
    out = {}
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


MODULES = modules()


def imports(name: str, path: Path, known: dict[str, Path] = MODULES):
    """The modules ``name`` imports: external ones by their name, mechgrade's own as
    ``mechgrade.<module>``. ``from P import x`` is resolved to the module or package ``P.x``
    when there is one (``from . import files``, ``from mechgrade import roster``)."""
    tree = _parsed(path.read_text(encoding="utf-8"))
    package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
    package = [p for p in package if p]
    # Imports under "if TYPE_CHECKING:" never run: they name types for annotations only (its
    # "else:" branch does run).
    type_only = {id(inner) for node in ast.walk(tree) if isinstance(node, ast.If)
                 and _is_type_checking(node.test)
                 for statement in node.body for inner in ast.walk(statement)}
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
                elif target.startswith("mechgrade"):
                    yield target
                else:  # "from sympy import physics" imports sympy.physics
                    yield candidate


@lru_cache(maxsize=None)
def _parsed(text: str) -> ast.Module:
    """A module's tree, parsed once for every check that reads it (a planted copy is other
    text, so it is parsed afresh)."""
    return ast.parse(text)


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or \
        (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


IMPORTERS = ("import_module", "__import__")
"""The functions that import a module named at run time (``importlib``'s, the builtin)."""


def dynamic_imports(path: Path) -> list[int]:
    """The lines where ``path`` imports a module named at run time: a call of one of
    :data:`IMPORTERS`, by its name, an attribute (``builtins.__import__``) or another name it
    was imported as (``from importlib import import_module as load``)."""
    tree = _parsed(path.read_text(encoding="utf-8"))
    names = {*IMPORTERS, *(alias.asname for node in ast.walk(tree)
                           if isinstance(node, ast.ImportFrom)
                           for alias in node.names if alias.name in IMPORTERS and alias.asname)}
    return [node.lineno for node in ast.walk(tree) if isinstance(node, ast.Call) and (
        (isinstance(node.func, ast.Attribute) and node.func.attr in IMPORTERS)
        or (isinstance(node.func, ast.Name) and node.func.id in names))]


STR_ENUM_HOME = "expressions.functions"
"""The one module that imports ``enum.StrEnum`` (Python 3.11's; it spells it out on 3.10, which
pyproject.toml still supports); every other module takes it from there."""


def str_enum_imports(path: Path) -> list[int]:
    """The lines where ``path`` takes ``StrEnum`` from :mod:`enum`, or defines a str enum of
    its own (a class deriving from both ``str`` and ``Enum``)."""
    tree = _parsed(path.read_text(encoding="utf-8"))
    return [node.lineno for node in ast.walk(tree)
            if (isinstance(node, ast.ImportFrom) and node.module == "enum"
                and any(alias.name == "StrEnum" for alias in node.names))
            or (isinstance(node, ast.ClassDef)
                and {"str", "Enum"} <= {b.id for b in node.bases if isinstance(b, ast.Name)})]


def own(target: str) -> str | None:
    """A mechgrade module's name relative to mechgrade, or ``None`` for another library."""
    if target == "mechgrade":
        return ""
    return target[len("mechgrade."):] if target.startswith("mechgrade.") else None


def violations(name: str, path: Path, known: dict[str, Path] = MODULES) -> list[str]:
    """What ``name`` (at ``path``) imports against the layering rules, one line each."""
    found = []
    mine = layer(name)
    for target in imports(name, path, known):
        if target.startswith("sympy.physics") and mine != "mechanics":
            found.append(f"{name} imports {target} (only mechanics/ may)")
        if (target == "sympy" or target.startswith("sympy.")) and mine in ("report", "export"):
            found.append(f"{name} imports {target} ({mine}/ never imports sympy)")
        other = own(target)
        if other is None or name == "__main__":
            continue
        if ORDER.index(layer(other)) > ORDER.index(mine):
            found.append(f"{name} imports {target} (layer {layer(other)} after {mine})")
        elif mine == "base" == layer(other) and base_rank(other) > base_rank(name):
            found.append(f"{name} imports {target} (later in the base layer's order)")
    if name not in DYNAMIC_IMPORTERS:
        found += [f"{name}:{line} imports a module named at run time"
                  for line in dynamic_imports(path)]
    if name != STR_ENUM_HOME:
        found += [f"{name}:{line} takes StrEnum from enum or makes its own (only "
                  f"{STR_ENUM_HOME} may)" for line in str_enum_imports(path)]
    return found


@pytest.mark.parametrize("name, path", list(MODULES.items()), ids=list(MODULES))
def test_module_imports_only_earlier_layers(name, path):
    assert violations(name, path) == []


def test_every_module_has_a_place_in_the_base_order():
    for name in MODULES:
        if layer(name) == "base":
            base_rank(name)  # raises ValueError for a base module the order does not list


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


@pytest.mark.parametrize("importer, text", [
    ("report.page", "from sympy import physics\n"),
    ("solve.plan", "from sympy import physics\n"),
    ("solve.plan", "from sympy.physics import mechanics\n"),
    ("report.page", "import sympy\n"),
    ("export.csvfile", "from sympy import Symbol\n"),
    ("spec.model", "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    pass\n"
                   "else:\n    from ..solve import plan\n"),
    ("spec.model", "import importlib\nplan = importlib.import_module('mechgrade.solve.plan')\n"),
    ("spec.model", "from importlib import import_module\nimport_module('x')\n"),
    ("spec.model", "__import__('mechgrade.solve.plan')\n"),
    ("spec.model", "from importlib import import_module as load\nload('mechgrade.solve')\n"),
    ("spec.model", "import builtins\nbuiltins.__import__('mechgrade.solve')\n"),
    ("spec.model", "from enum import StrEnum\n"),
    ("spec.model", "from enum import Enum\nclass Kind(str, Enum):\n    A = 'a'\n"),
    ("errors", "from . import files\n"),
    ("files", "from .expressions import syntax\n"),
    ("grade.run", "from .. import cli\n"),
])
def test_a_planted_forbidden_import_is_caught(tmp_path, importer, text):
    known = fake_modules(tmp_path, {"": "", "errors": "", "files": "", "expressions": "",
                                    "expressions.syntax": "", "spec": "", "spec.model": "",
                                    "solve": "", "solve.plan": "", "grade": "", "grade.run": "",
                                    "report": "", "report.page": "", "export": "",
                                    "export.csvfile": "", "cli": ""})
    assert violations(importer, known[importer], known) == []
    known[importer].write_text(text, encoding="utf-8")
    assert violations(importer, known[importer], known) != []


def test_imports_for_annotations_only_are_allowed(tmp_path):
    known = fake_modules(tmp_path, {"": "", "spec": "", "spec.model": "", "solve": "",
                                    "solve.plan": ""})
    known["spec.model"].write_text("import typing\nif typing.TYPE_CHECKING:\n"
                                   "    from ..solve import plan\n", encoding="utf-8")
    assert violations("spec.model", known["spec.model"], known) == []


# --- the whole check, on a copy of the package with a forbidden import planted -------------------

def package_faults(known: dict[str, Path]) -> list[str]:
    """Everything the architecture tests above find in the package ``known`` (every module's
    violations, a base module missing from the base order, import cycles), one line each."""
    found = [v for name, path in known.items() for v in violations(name, path, known)]
    for name in known:
        if layer(name) == "base":
            try:
                base_rank(name)
            except ValueError:
                found.append(f"{name} has no place in the base layer's order")
    found += [" -> ".join(cycle) for cycle in cycles(import_graph(known))]
    return found


PLANTED = {
    "sympy.physics outside mechanics": ("solve/plan.py", "from sympy import physics\n",
                                        "solve.plan imports sympy.physics"),
    "an import in the else: of TYPE_CHECKING": (
        "spec/model.py", "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    pass\n"
        "else:\n    from ..solve import plan\n", "spec.model imports mechgrade.solve.plan"),
    "importlib.import_module outside its call sites": (
        "grade/run.py", "import importlib\n_m = importlib.import_module('mechgrade.report')\n",
        "imports a module named at run time"),
    "an order violation inside the base layer": (
        "errors.py", "from . import files\n", "errors imports mechgrade.files"),
    "a report importing sympy": ("report/output.py", "import sympy\n",
                                 "report.output imports sympy"),
    "an import of the CLI": ("grade/run.py", "from ..cli import main\n",
                             "grade.run imports mechgrade.cli"),
}


@pytest.fixture(scope="module")
def package_copy(tmp_path_factory) -> Path:
    """A copy of mechgrade's package folder, untouched (each test plants in its own copy)."""
    copy = tmp_path_factory.mktemp("pristine") / "mechgrade"
    shutil.copytree(SRC, copy, ignore=shutil.ignore_patterns("__pycache__", "*.json", "*.j2"))
    return copy


# end-to-end checks of the checker: each copies the whole package and checks it (5-12 s)
@pytest.mark.slow
def test_the_package_as_it_is_has_no_fault(package_copy):
    assert package_faults(modules(package_copy)) == []


@pytest.mark.slow
@pytest.mark.parametrize("planted", list(PLANTED), ids=list(PLANTED))
def test_a_forbidden_import_planted_in_a_copy_of_the_package_fails_the_check(
        package_copy, tmp_path, planted):
    module, text, said = PLANTED[planted]
    copy = tmp_path / "mechgrade"
    shutil.copytree(package_copy, copy)
    target = copy / module
    target.write_text(target.read_text(encoding="utf-8") + "\n" + text, encoding="utf-8")
    faults = package_faults(modules(copy))
    assert faults and all(said in f or module.replace("/", ".")[:-3] in f for f in faults)
    assert any(said in f for f in faults), faults

