"""The on-disk cache of compiled problems: what deriving a problem with sympy produced, kept so
that solving it again (``mechgrade check`` of an unchanged file) needs no sympy at all: a
kinematics problem's plan (:mod:`.plan`) and symbolic answers (:mod:`.instant`), a dynamics
problem's solutions, for each givens and objectives asked (:mod:`.stored`), and a checked
file's report (:func:`mechgrade.check.check_problem`, keyed by the file's path and bytes).

An entry is a JSON document named by :func:`problem_key`, a SHA-256 of the loaded problem's
canonical text (its ``repr``: every field, locations included, so a moved line gives messages
that point at the right place), mechgrade's version and a fingerprint of its source files,
sympy's version and :data:`FORMAT`. Keying on the loaded problem rather than the file's bytes
also covers problems made in memory (a problem's kinematic part, a spec read from text); an
upgrade of mechgrade or sympy, or an edit of mechgrade's code, gives new keys, never a stale
entry.

Where: ``$MECHGRADE_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/mechgrade``, else
``~/.cache/mechgrade``. ``MECHGRADE_NO_CACHE=1`` turns the cache off (nothing read or written).
Deleting the folder clears it. Its size is bounded (:func:`prune`): past :data:`MAX_MB`
megabytes (``$MECHGRADE_CACHE_MAX_MB``), the entries used least recently are removed.

Trust model: the folder is the user's own, as writable by them as their shell start-up files,
so an entry is not a secret to guard but it is never trusted blindly either. Entries are JSON
(never pickle). The only code in them is the source sympy's ``lambdify`` printed for the
problem's functions; before it is compiled, :func:`numpy_function` checks that it is nothing
but one function of numbers: arithmetic, calls of a fixed list of numpy functions, and lists
(no attribute access, no imports, no other names), run with no builtins. An entry that is
corrupt, truncated, of another format or key, or fails that check is ignored and written
again: it can cost time, never a wrong answer or a crash.

>>> import tempfile, os
>>> os.environ["MECHGRADE_CACHE_DIR"] = tempfile.mkdtemp()
>>> store("k" * 64, {"answer": 42}); load("k" * 64)
{'answer': 42}
>>> f = numpy_function("def f(x, y):\\n    x0 = sin(x)\\n    return array([[x0 + y**2]])\\n")
>>> f(0.0, 3.0).tolist()
[[9.0]]
>>> del os.environ["MECHGRADE_CACHE_DIR"]
"""

from __future__ import annotations

import ast
import hashlib
import json
import os
import itertools
import re
from functools import lru_cache
from pathlib import Path
from typing import Any, Callable

import numpy as np

from .. import __version__
from ..errors import Location, MechgradeError
from ..files import write_text

FORMAT = 2
"""The layout of an entry; raised whenever what is stored changes."""

MAX_MB = 200
"""The megabytes of entries the folder is kept under, unless ``$MECHGRADE_CACHE_MAX_MB`` says
otherwise (a value that is not a number is ignored)."""

PRUNE_EVERY = 100
"""Stores between two looks at the folder's size (the first store of a process looks)."""

NUMPY_NAMES = frozenset((
    "sin", "cos", "tan", "arcsin", "arccos", "arctan", "arctan2", "sinh", "cosh", "tanh",
    "arcsinh", "arccosh", "arctanh", "exp", "expm1", "log", "log1p", "log2", "log10", "sqrt",
    "cbrt", "abs", "absolute", "sign", "floor", "ceil", "hypot", "power", "minimum", "maximum",
    "amin", "amax", "heaviside", "select", "where", "less", "less_equal", "greater",
    "greater_equal", "equal", "not_equal", "logical_and", "logical_or", "logical_not",
    "isnan", "isinf", "real", "imag", "conjugate", "angle", "mod", "array", "zeros", "ones",
    "pi", "e", "nan", "inf"))
"""The numpy names generated functions may use (what sympy's numpy printer writes)."""

_OPERATORS = (ast.Add, ast.Sub, ast.Mult, ast.Div, ast.Pow, ast.Mod, ast.FloorDiv, ast.USub,
              ast.UAdd, ast.Not, ast.And, ast.Or, ast.Lt, ast.LtE, ast.Gt, ast.GtE, ast.Eq,
              ast.NotEq, ast.Load, ast.Store)
_EXPRESSIONS = (ast.BinOp, ast.UnaryOp, ast.BoolOp, ast.Compare, ast.Call, ast.Name,
                ast.Constant, ast.List, ast.Tuple, ast.keyword)


def enabled() -> bool:
    """Whether the cache is used (``MECHGRADE_NO_CACHE`` unset, empty or ``0``)."""
    return os.environ.get("MECHGRADE_NO_CACHE", "") in ("", "0")


def folder() -> Path:
    """Where entries are kept (see the module's docstring)."""
    if os.environ.get("MECHGRADE_CACHE_DIR"):
        return Path(os.environ["MECHGRADE_CACHE_DIR"])
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "mechgrade"


def problem_key(problem) -> str | None:
    """The key of a problem's entries, or ``None`` when it has no canonical text (a field
    whose ``repr`` is an object's identity) and so cannot be cached.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
    >>> len(problem_key(problem)), problem_key(problem) == problem_key(problem)
    (64, True)
    """
    text = repr(problem)
    if " at 0x" in text:
        return None
    return digest(*code_key(), text)


def code_key(*libraries: str) -> tuple[Any, ...]:
    """What an entry's key names of the code that made it: :data:`FORMAT`, mechgrade's
    version and source files, sympy's version, and each of ``libraries``' (import names)."""
    return (FORMAT, __version__, _source_fingerprint(), _sympy_version(),
            *(package_version(name, "version.py") for name in libraries))


def digest(*parts: Any) -> str:
    """SHA-256 (hex) of ``parts`` as JSON: the name of one entry."""
    return hashlib.sha256(json.dumps(parts, default=repr).encode()).hexdigest()


def load(key: str) -> Any:
    """The data stored under ``key``, or ``None`` when there is none or it is unreadable
    (missing, corrupt, truncated, another format or another key's). An entry read is marked
    used now (its modification time), for :func:`prune`."""
    path = folder() / f"{key}.json"
    try:
        with open(path, encoding="utf-8") as handle:
            entry = json.load(handle)
    except (OSError, ValueError):
        return None
    try:
        os.utime(path)
    except OSError:
        pass  # a read-only folder, or pruned meanwhile: it was read all the same
    if not isinstance(entry, dict) or entry.get("format") != FORMAT or entry.get("key") != key:
        return None
    return entry.get("data")


def store(key: str, data: Any) -> None:
    """Keep ``data`` (plain JSON) under ``key``, written atomically; a cache that cannot be
    written (a read-only home, a full disk) is no error: the next run derives again. Every
    :data:`PRUNE_EVERY` stores of a process, the first included, the folder is pruned."""
    try:
        place = folder()
        place.mkdir(parents=True, exist_ok=True)
        write_text(place / f"{key}.json", json.dumps(
            {"format": FORMAT, "key": key, "data": data}, separators=(",", ":")))
    except (OSError, MechgradeError):
        return
    if next(_stores) % PRUNE_EVERY == 0:
        prune(limit())


_stores = itertools.count()


def limit() -> int:
    """The bytes of entries the folder is kept under (:data:`MAX_MB`)."""
    try:
        megabytes = float(os.environ.get("MECHGRADE_CACHE_MAX_MB") or MAX_MB)
    except ValueError:
        megabytes = MAX_MB
    return max(0, int(megabytes * 1024 * 1024))


def prune(bound: int) -> None:
    """When the folder's entries take more than ``bound`` bytes, remove the least recently
    used ones (oldest modification time first) until they take three quarters of it, so that
    the next stores do not prune again at once. Another process may store, read or prune
    meanwhile: an entry gone already is no error, and one removed under a reader is a miss.

    >>> import tempfile, time
    >>> os.environ["MECHGRADE_CACHE_DIR"] = tempfile.mkdtemp()
    >>> for name in "abc":
    ...     store(name * 64, "x" * 1000)
    ...     os.utime(folder() / f"{name * 64}.json", (time.time(), time.time() + ord(name)))
    >>> prune(2500); sorted(p.name[0] for p in folder().iterdir())
    ['c']
    >>> del os.environ["MECHGRADE_CACHE_DIR"]
    """
    found = []
    try:
        with os.scandir(folder()) as entries:
            for entry in entries:
                if entry.name.endswith(".json"):
                    try:
                        info = entry.stat()
                    except OSError:
                        continue  # removed meanwhile
                    found.append((info.st_mtime_ns, info.st_size, entry.path))
    except OSError:
        return
    total = sum(size for _, size, _ in found)
    if total <= bound:
        return
    for _, size, path in sorted(found):
        if total <= bound * 3 // 4:
            break
        try:
            os.remove(path)
        except FileNotFoundError:
            pass  # another process pruned it
        except OSError:
            continue
        total -= size


def where_data(where: Location) -> list:
    """A location as an entry keeps it."""
    return [where.file, where.line, where.column, where.field]


def where_from(data: Any) -> Location:
    """The location :func:`where_data` gave ``data`` for."""
    file, line, column, field = data
    return Location(None if file is None else str(file), None if line is None else int(line),
                    None if column is None else int(column),
                    None if field is None else str(field))


class UnsafeSource(ValueError):
    """Generated source that is not one plain function of numbers."""


def numpy_function(source: str) -> Callable:
    """The function ``source`` defines, compiled with only :data:`NUMPY_NAMES` in scope and
    no builtins, after checking it is one function of numbers (:class:`UnsafeSource` if not).

    >>> numpy_function("def f(x):\\n    return __import__('os')\\n")
    Traceback (most recent call last):
    ...
    mechgrade.solve.cache.UnsafeSource: only calls of numpy functions are allowed
    """
    tree = ast.parse(source)
    if len(tree.body) != 1 or not isinstance(tree.body[0], ast.FunctionDef):
        raise UnsafeSource("expected one function definition")
    function = tree.body[0]
    args = function.args
    if function.decorator_list or function.returns or args.vararg or args.kwarg \
            or args.posonlyargs or args.kwonlyargs or args.defaults:
        raise UnsafeSource("expected a function of plain positional arguments")
    names = {a.arg for a in args.args}
    if not function.body or not isinstance(function.body[-1], ast.Return):
        raise UnsafeSource("expected the function to end in a return")
    for statement in function.body:
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1 \
                and isinstance(statement.targets[0], ast.Name):
            _check_expression(statement.value, names)
            names.add(statement.targets[0].id)
        elif isinstance(statement, ast.Return) and statement.value is not None:
            _check_expression(statement.value, names)
        else:
            raise UnsafeSource(f"statement {type(statement).__name__} is not allowed")
    namespace: dict[str, Any] = {"__builtins__": {}, **_numpy_namespace()}
    exec(compile(tree, "<mechgrade-cache>", "exec"), namespace)
    return namespace[function.name]


def _check_expression(node: ast.AST, names: set[str]) -> None:
    for child in ast.walk(node):
        if isinstance(child, ast.Name):
            if child.id not in names and child.id not in NUMPY_NAMES:
                raise UnsafeSource(f"name {child.id!r} is not allowed")
        elif isinstance(child, ast.Call):
            if not isinstance(child.func, ast.Name) or child.func.id not in NUMPY_NAMES:
                raise UnsafeSource("only calls of numpy functions are allowed")
        elif isinstance(child, ast.Constant):
            if not isinstance(child.value, (int, float, complex)):
                raise UnsafeSource("only numeric constants are allowed")
        elif isinstance(child, ast.keyword):
            if child.arg is None:
                raise UnsafeSource("** arguments are not allowed")
        elif not isinstance(child, _EXPRESSIONS + _OPERATORS):
            raise UnsafeSource(f"{type(child).__name__} is not allowed")


@lru_cache(maxsize=1)
def _numpy_namespace() -> dict[str, Any]:
    return {name: getattr(np, name) for name in NUMPY_NAMES if hasattr(np, name)}


def same_namespace(function: Callable) -> bool:
    """Whether the numpy names ``function`` (a lambdified one) sees are those
    :func:`numpy_function` gives: only then is its source cached."""
    mine = _numpy_namespace()
    return all(function.__globals__.get(name) is value for name, value in mine.items()
               if name in function.__code__.co_names)


def _sympy_version() -> str:
    return package_version("sympy", "release.py")


@lru_cache(maxsize=16)
def package_version(name: str, release: str) -> str:
    """A package's version as read from its ``release`` file (without importing it: asking
    the package metadata takes as long as a whole warm check), and the size and modification
    time of its ``__init__.py``, which any upgrade rewrites."""
    import importlib.util

    spec = importlib.util.find_spec(name)
    if spec is None or spec.origin is None:
        return "none"
    try:
        found = re.search(r"^(?:__version__|version)\s*=\s*['\"]([^'\"]+)",
                          Path(spec.origin).with_name(release).read_text(), re.MULTILINE)
    except OSError:
        found = None
    info = os.stat(spec.origin)
    return f"{found.group(1) if found else ''}:{info.st_size}:{info.st_mtime_ns}"


@lru_cache(maxsize=1)
def _source_fingerprint() -> str:
    """Sizes and modification times of mechgrade's own source files (and its schema): an
    edited derivation (a working copy, not only a new version) never reads an entry made by
    the old code."""
    stamps: list[tuple[str, int, int]] = []

    def scan(folder: str, prefix: str) -> None:
        with os.scandir(folder) as found:
            for entry in sorted(found, key=lambda e: e.name):
                if entry.name.endswith((".py", ".json")) and entry.is_file():
                    info = entry.stat()
                    stamps.append((prefix + entry.name, info.st_size, info.st_mtime_ns))
                elif entry.name != "__pycache__" and entry.is_dir():
                    scan(entry.path, f"{prefix}{entry.name}/")

    scan(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "")
    return digest(stamps)
