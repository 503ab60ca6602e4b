"""Functions sympy's ``lambdify`` printed for a problem, read back from the disk cache
(:mod:`.cache`) as source and compiled only once they are checked to be one bounded function
of numbers: what sympy's numpy printer writes, and nothing that could run other code, hang,
exhaust memory or give a complex number, however the source came to be what it is. A function
refused is derived again with sympy: it costs time, never a wrong answer.

>>> f = numpy_function("def f(x, y):\\n    x0 = sin(x)\\n    return array([[x0 + y**2]])\\n")
>>> f(0.0, 3.0).tolist()
[[9.0]]
"""

from __future__ import annotations

import ast
import math
from functools import lru_cache
from typing import Any, Callable

import numpy as np

NUMPY_NAMES = frozenset((
    "sin", "cos", "tan", "arcsin", "arccos", "arctan", "arctan2", "sinh", "cosh", "tanh",
    "arcsinh", "arccosh", "arctanh", "exp", "expm1", "log", "log1p", "log2", "log10", "sqrt",
    "cbrt", "abs", "absolute", "sign", "floor", "ceil", "hypot", "power", "minimum", "maximum",
    "heaviside", "select", "where", "less", "less_equal", "greater", "greater_equal", "equal",
    "not_equal", "logical_and", "logical_or", "logical_not", "isnan", "isinf", "real", "imag",
    "conjugate", "angle", "mod", "array", "zeros", "ones", "pi", "e", "nan"))
"""The numpy names generated functions may use (what sympy's numpy printer writes)."""

MAX_SOURCE_CHARS = 100_000
MAX_NODES = 20_000
MAX_DEPTH = 200
"""Bounds of a generated function's source: characters, parts (each number, name, operation
or call) and nesting of parts (the shipped problems' largest: 863 characters, 224
parts, 14 deep). Python's own compiler fails on a few hundred levels; past these bounds a
function is not cached (derived each time)."""

MAX_ELEMENTS = 10_000
"""The most elements of an array of zeros or ones a generated function may make."""

MAX_INTEGER = 2 ** 53
"""The largest whole number a constant part of a generated function may come to."""


class UnsafeSource(ValueError):
    """Generated source that is not one bounded function of numbers."""


def numpy_function(source: str) -> Callable:
    """The function ``source`` defines, compiled with only :data:`NUMPY_NAMES` in scope and
    no builtins, once it is checked to be one bounded function of numbers
    (:class:`UnsafeSource` if not): plain positional arguments, assignments of names once and
    a return; arithmetic, comparisons, numpy's element-wise functions (each with its own
    number of arguments), lists only as the rows of a returned ``array`` or the cases of
    ``select``, arrays only returned; every constant part a finite real number (whole ones
    up to :data:`MAX_INTEGER`: no ``10**10**10``), ``nan`` only as ``select``'s default;
    within :data:`MAX_SOURCE_CHARS`, :data:`MAX_NODES` and :data:`MAX_DEPTH`.

    >>> numpy_function("def f(x):\\n    return __import__('os')\\n")
    Traceback (most recent call last):
    ...
    mechgrade.solve.generated.UnsafeSource: only calls of numpy functions are allowed
    >>> numpy_function("def f(x):\\n    return x**10**10**10\\n")
    Traceback (most recent call last):
    ...
    mechgrade.solve.generated.UnsafeSource: a constant larger than 9007199254740992
    """
    if not isinstance(source, str):
        raise UnsafeSource("expected a function's source")
    if len(source) > MAX_SOURCE_CHARS:
        raise UnsafeSource(f"expected at most {MAX_SOURCE_CHARS} characters")
    try:
        tree = ast.parse(source)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        # MemoryError: what Python's parser raises for nesting too deep for its stack
        raise UnsafeSource("expected the source of a function") from None
    function = _Checker().function(tree)
    namespace: dict[str, Any] = {"__builtins__": {}, **_numpy_namespace()}
    try:
        exec(compile(tree, "<mechgrade-cache>", "exec"), namespace)
    except (RecursionError, MemoryError, SyntaxError, ValueError):
        raise UnsafeSource("expected a function Python can compile") from None
    return namespace[function.name]


_BINARY: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b, ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b, ast.Mod: lambda a, b: a % b,
    ast.FloorDiv: lambda a, b: a // b}
_UNARY: dict[type, Callable[[Any], Any]] = {
    ast.USub: lambda a: -a, ast.UAdd: lambda a: +a, ast.Not: lambda a: not a}
_COMPARE: dict[type, Callable[[Any, Any], bool]] = {
    ast.Lt: lambda a, b: a < b, ast.LtE: lambda a, b: a <= b, ast.Gt: lambda a, b: a > b,
    ast.GtE: lambda a, b: a >= b, ast.Eq: lambda a, b: a == b, ast.NotEq: lambda a, b: a != b}
_ARITY = {"array": 1, "zeros": 1, "ones": 1, "select": 2, "where": 3, "real": 1, "imag": 1,
          "angle": 1}
_ARRAYS = frozenset(("array", "zeros", "ones"))
_CONSTANTS = frozenset(("pi", "e", "nan"))
_VARIABLE = object()
"""What a part that depends on the arguments folds to."""


class _Checker:
    """Checks a function's tree (see :func:`numpy_function`), folding its constant parts with
    bounds as it goes."""

    def __init__(self) -> None:
        self.names: dict[str, Any] = {}  # the names bound: constant values, or _VARIABLE
        self.parts = 0
        self.depth = 0

    def enter(self) -> None:
        """One more part, one level deeper (checked before going on: the checker recurses)."""
        self.parts += 1
        self.depth += 1
        if self.parts > MAX_NODES:
            raise UnsafeSource(f"expected at most {MAX_NODES} parts")
        if self.depth > MAX_DEPTH:
            raise UnsafeSource(f"expected parts nested at most {MAX_DEPTH} deep")

    def function(self, tree: ast.Module) -> ast.FunctionDef:
        if len(tree.body) != 1 or not isinstance(tree.body[0], ast.FunctionDef):
            raise UnsafeSource("expected one function definition")
        function = tree.body[0]
        args = function.args
        if function.decorator_list or function.returns or args.vararg or args.kwarg \
                or args.posonlyargs or args.kwonlyargs or args.defaults:
            raise UnsafeSource("expected a function of plain positional arguments")
        for a in args.args:
            self.bind(a.arg, _VARIABLE)
        if not function.body or not isinstance(function.body[-1], ast.Return) \
                or function.body[-1].value is None:
            raise UnsafeSource("expected the function to end in a return")
        for statement in function.body[:-1]:
            if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1
                    and isinstance(statement.targets[0], ast.Name)):
                raise UnsafeSource(f"statement {type(statement).__name__} is not allowed")
            self.bind(statement.targets[0].id, self.scalar(statement.value))
        self.returned(function.body[-1].value)
        return function

    def bind(self, name: str, value: Any) -> None:
        # a symbol may shadow a constant (a coefficient of restitution named e), never a
        # function the body calls
        if name in self.names or name.startswith("__") or \
                (name in NUMPY_NAMES and name not in _CONSTANTS):
            raise UnsafeSource(f"name {name!r} may not be bound here")
        self.names[name] = value

    def returned(self, node: ast.expr) -> None:
        """What a function may return: an array built from a literal, or a number."""
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) \
                and node.func.id in _ARRAYS:
            self.arity(node, node.func.id)
            if node.func.id == "array":
                self.rows(node.args[0])
            else:
                self.shape(node.args[0])
        else:
            self.scalar(node)

    def rows(self, node: ast.expr) -> tuple[int, ...]:
        """An array's literal: lists of equal length down to numbers; its shape."""
        self.enter()
        try:
            return self._rows(node)
        finally:
            self.depth -= 1

    def _rows(self, node: ast.expr) -> tuple[int, ...]:
        if not isinstance(node, ast.List):
            self.scalar(node)
            return ()
        shapes = {self.rows(item) for item in node.elts}
        if len(shapes) > 1:
            raise UnsafeSource("expected the rows of an array to have one length")
        return (len(node.elts), *(shapes.pop() if shapes else ()))

    def shape(self, node: ast.expr) -> None:
        if not isinstance(node, ast.Tuple) or not node.elts:
            raise UnsafeSource("expected an array's shape as numbers")
        count = 1
        for item in node.elts:
            size = self.scalar(item)
            if type(size) is not int or size < 0:
                raise UnsafeSource("expected an array's shape as whole numbers")
            count *= size
            if count > MAX_ELEMENTS:
                raise UnsafeSource(f"expected arrays of at most {MAX_ELEMENTS} elements")

    def arity(self, node: ast.Call, name: str) -> None:
        function = _numpy_namespace().get(name)
        wanted = function.nin if isinstance(function, np.ufunc) else _ARITY.get(name)
        if wanted is None or len(node.args) != wanted or any(
                isinstance(a, ast.Starred) for a in node.args):
            raise UnsafeSource(f"expected {name} with its own number of arguments")
        allowed = {"default"} if name == "select" else set()
        for keyword in node.keywords:
            if keyword.arg not in allowed:
                raise UnsafeSource(f"keyword {keyword.arg!r} is not allowed")

    def scalar(self, node: ast.expr) -> Any:
        """Check a part that gives a number (or numbers, one per column of the arguments):
        its value when it is constant, else ``_VARIABLE``."""
        self.enter()
        try:
            return self._scalar(node)
        finally:
            self.depth -= 1

    def _scalar(self, node: ast.expr) -> Any:
        if isinstance(node, ast.Constant):
            value = node.value
            if type(value) not in (int, float, bool):
                raise UnsafeSource("only real numeric constants are allowed")
            return self.bounded(value)
        if isinstance(node, ast.Name):
            if node.id in self.names:
                return self.names[node.id]
            if node.id in ("pi", "e"):
                return getattr(math, node.id)
            raise UnsafeSource(f"name {node.id!r} is not allowed")
        if isinstance(node, ast.BinOp):
            return self.fold(node.op, self.scalar(node.left), self.scalar(node.right))
        if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
            operand = self.scalar(node.operand)
            return _VARIABLE if operand is _VARIABLE else \
                self.constant(lambda: _UNARY[type(node.op)](operand))
        if isinstance(node, ast.Compare) and all(type(op) in _COMPARE for op in node.ops):
            values = [self.scalar(node.left), *(self.scalar(c) for c in node.comparators)]
            if _VARIABLE in values:
                return _VARIABLE
            return all(_COMPARE[type(op)](a, b)
                       for op, a, b in zip(node.ops, values, values[1:]))
        if isinstance(node, ast.BoolOp):
            values = [self.scalar(v) for v in node.values]
            return _VARIABLE if _VARIABLE in values else \
                (all(values) if isinstance(node.op, ast.And) else any(values))
        if isinstance(node, ast.Call):
            return self.call(node)
        raise UnsafeSource(f"{type(node).__name__} is not allowed")

    def call(self, node: ast.Call) -> Any:
        if not isinstance(node.func, ast.Name) or node.func.id not in NUMPY_NAMES \
                or node.func.id in _CONSTANTS:
            raise UnsafeSource("only calls of numpy functions are allowed")
        name = node.func.id
        if name in _ARRAYS:
            raise UnsafeSource("arrays are allowed only as what a function returns")
        self.arity(node, name)
        if name == "select":
            conditions, choices = node.args
            if not (isinstance(conditions, ast.List) and isinstance(choices, ast.List)
                    and len(conditions.elts) == len(choices.elts)):
                raise UnsafeSource("expected select's conditions and choices as two lists "
                                   "of one length")
            for item in conditions.elts + choices.elts:
                self.scalar(item)
            for keyword in node.keywords:
                if not (isinstance(keyword.value, ast.Name) and keyword.value.id == "nan"):
                    self.scalar(keyword.value)
        else:
            for argument in node.args:
                self.scalar(argument)
        return _VARIABLE

    def fold(self, op: ast.operator, a: Any, b: Any) -> Any:
        if isinstance(op, ast.Pow):
            if a is _VARIABLE or b is _VARIABLE:
                return _VARIABLE  # numpy's power: a number of fixed size, however large
            if type(a) is int and type(b) is int and b > 0 and a.bit_length() * b > 64:
                raise UnsafeSource(f"a constant larger than {MAX_INTEGER}")
            return self.constant(lambda: a ** b)
        if type(op) not in _BINARY:
            raise UnsafeSource(f"{type(op).__name__} is not allowed")
        if a is _VARIABLE or b is _VARIABLE:
            return _VARIABLE
        return self.constant(lambda: _BINARY[type(op)](a, b))

    def constant(self, work: Callable[[], Any]) -> Any:
        try:
            value = work()
        except (ArithmeticError, ValueError):
            raise UnsafeSource("a constant part that cannot be worked out (a division by "
                               "zero, an overflow)") from None
        return self.bounded(value)

    @staticmethod
    def bounded(value: Any) -> Any:
        if type(value) is complex:
            raise UnsafeSource("only real numeric constants are allowed")
        if type(value) is int and abs(value) > MAX_INTEGER:
            raise UnsafeSource(f"a constant larger than {MAX_INTEGER}")
        if type(value) is float and not math.isfinite(value):
            raise UnsafeSource("only finite constants are allowed")
        return value


def lambdified(symbols, expr) -> Callable:
    """``expr`` as a numpy function of ``symbols`` (sympy's ``lambdify``, common
    subexpressions once) that gives one column's numbers the bits an array gives that column:
    a power is numpy's own (a square a product, every other ``power``), where ``**`` on numbers
    is the C library's ``pow``, which differs from numpy's loop in the last bit for about one
    value in twenty (one in a thousand for a square). A single solve calls its functions with
    numbers, a class with arrays (:func:`.columns.loud_call`): so a variant solved alone is,
    bit for bit, that variant solved in a class.

    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> f = lambdified([x, y], x**2 / y**3)
    >>> a = 35.84188522037357  # where pow(a, 2) is not a * a
    >>> bool(f(a, 1.1) == f(np.array([a]), np.array([1.1]))[0]), a**2 == a * a
    (True, False)
    """
    import sympy as sp
    from sympy.printing.numpy import NumPyPrinter

    class ArrayPowers(NumPyPrinter):
        def _print_Pow(self, expr, rational=False):
            e = expr.exp
            if rational or not expr.is_commutative or e in (sp.S.Half, -sp.S.Half, -1):
                return super()._print_Pow(expr, rational)  # sqrt(x), 1/sqrt(x), 1/x
            base = self._print(expr.base)
            if e == 2 and expr.base.is_Symbol:
                return f"({base}*{base})"  # (numpy's a**2 is a*a)
            # a negative whole power of a whole number is an error in numpy: as a float
            power = e.evalf() if e.is_Integer and e.is_negative else e
            return f"{self._module_format('numpy.power')}({base}, {self._print(power)})"

    printer = ArrayPowers({"fully_qualified_modules": False, "inline": True,
                           "allow_unknown_functions": True, "user_functions": {}})
    return sp.lambdify(symbols, expr, modules="numpy", cse=True, docstring_limit=0,
                       printer=printer)


@lru_cache(maxsize=1)
def _numpy_namespace() -> dict[str, Any]:
    return {name: getattr(np, name) for name in NUMPY_NAMES if hasattr(np, name)}


def same_namespace(function: Callable) -> bool:
    """Whether the numpy names ``function`` (a lambdified one) sees are those
    :func:`numpy_function` gives: only then is its source cached."""
    mine = _numpy_namespace()
    return all(function.__globals__.get(name) is value for name, value in mine.items()
               if name in function.__code__.co_names)


