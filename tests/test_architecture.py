"""Imports point one way: spec -> mechanics -> solve -> grade -> report/export -> cli."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "mechgrade"
# Each layer may import only from itself and the layers listed before it.
ORDER = ["base", "spec", "mechanics", "solve", "check", "grade", "export", "report", "cli"]
BASE = {"errors", "units", "yamlio", "files", "resources", "expressions", "roster", "parallel",
        "__init__", "__main__"}


def layer(module: str) -> str:
    top = module.split(".")[0]
    return "base" if top in BASE else top


def modules():
    for path in sorted(SRC.rglob("*.py")):
        name = ".".join(path.relative_to(SRC).with_suffix("").parts)
        yield name, path


def imports(name: str, path: Path):
    tree = ast.parse(path.read_text())
    package = name.split(".")[:-1] if not path.name == "__init__.py" else name.split(".")
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
                yield "mechgrade." + target if target else "mechgrade"
            else:
                yield node.module or ""


@pytest.mark.parametrize("name, path", list(modules()), ids=[n for n, _ in modules()])
def test_module_imports_only_earlier_layers(name, path):
    own = ORDER.index(layer(name))
    for target in imports(name, path):
        if target.startswith("sympy.physics"):
            assert layer(name) == "mechanics", f"{name} imports {target}"
        if target.startswith("sympy"):
            assert layer(name) not in ("report", "export"), f"{name} imports {target}"
        if target.startswith("mechgrade."):
            other = layer(target[len("mechgrade."):])
            if name == "__main__":
                continue
            assert ORDER.index(other) <= own, f"{name} imports {target}"
