"""The language's one table: every view (reader, sympy, numpy, constants, docs) agrees with it."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from mechgrade.errors import ExpressionError
from mechgrade.expressions.functions import (ALIASES, CONSTANT_FUNCTIONS, MATH_FUNCTIONS, Kind,
                                             OBJECTIVE_FUNCTIONS, TABLE, numpy_functions,
                                             sympy_functions)
from mechgrade.expressions.syntax import Call, Name, parse

DOCS = Path(__file__).resolve().parents[2] / "docs"
ARGUMENTS = {1: (0.37,), 2: (0.37, -0.81)}


def call_text(name: str, arity: int) -> str:
    return f"{name}({', '.join('xy'[:arity])})"


@pytest.mark.parametrize("written", sorted(set(MATH_FUNCTIONS) | set(ALIASES)))
def test_every_spelling_reads_as_its_canonical_function(written):
    canonical = MATH_FUNCTIONS[ALIASES.get(written, written)]
    node = parse(call_text(written, canonical.arity))
    assert node == Call(canonical.name, tuple(Name(a) for a in "xy"[:canonical.arity]))


def test_a_math_function_with_the_wrong_number_of_arguments_is_refused():
    with pytest.raises(ExpressionError, match=r"expected 2 arguments for atan2\(...\), found 1"):
        parse("atan2(x)")


@pytest.mark.parametrize("name", list(MATH_FUNCTIONS))
def test_sympy_and_numpy_implementations_agree(name):
    args = ARGUMENTS[MATH_FUNCTIONS[name].arity]
    symbolic = float(sympy_functions()[name](*(sp.Float(a) for a in args)))
    numeric = float(numpy_functions()[name](*(np.float64(a) for a in args)))
    assert numeric == pytest.approx(symbolic, rel=1e-12)


@pytest.mark.parametrize("name", sorted(CONSTANT_FUNCTIONS))
def test_constants_fold_to_the_numeric_value(name):
    assert CONSTANT_FUNCTIONS[name](0.37) == pytest.approx(float(numpy_functions()[name](0.37)))


def test_every_function_has_one_entry_and_a_description_naming_it():
    names = [f.name for f in TABLE]
    assert len(names) == len(set(names))
    assert not set(ALIASES) & set(names)
    for f in TABLE:
        assert f.doc.startswith(f"{f.name}("), f.name


def math_listing_after(text: str, marker: str) -> set[str]:
    """The words of the first backticked list starting with ``sin`` after ``marker``."""
    listing = re.search(r"`(sin [^`]+)`", text[text.index(marker):]).group(1)
    return set(listing.split())


def test_the_spec_docs_list_every_function_of_the_language():
    text = (DOCS / "spec.md").read_text(encoding="utf-8")
    listed = math_listing_after(text, "### The objective language")
    assert listed == set(MATH_FUNCTIONS)
    documented = set(re.findall(r"\| `(\w+)\(", text)) | set(re.findall(r", `(\w+)\(", text))
    assert set(OBJECTIVE_FUNCTIONS) <= documented, set(OBJECTIVE_FUNCTIONS) - documented


def test_the_answer_docs_list_every_math_function_students_may_write():
    text = (DOCS / "answers.md").read_text(encoding="utf-8")
    listed = math_listing_after(text, "**Expressions**")
    assert set(MATH_FUNCTIONS) <= listed <= set(MATH_FUNCTIONS) | set(ALIASES)


def test_reading_an_expression_imports_neither_sympy_nor_numpy():
    probe = ("import sys\nfrom mechgrade.expressions.syntax import parse, constant_value\n"
             "constant_value(parse('sqrt(2) + atan2(x, 1) + ln(y)'.replace('x', '1')"
             ".replace('y', '2')))\n"
             "print(sorted(m for m in ('sympy', 'numpy') if m in sys.modules))")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                          timeout=60, check=True)
    assert done.stdout.strip() == "[]"


def test_the_origin_a_function_needs_belongs_to_one_of_its_frame_arguments():
    needing = {f.name: f.args[f.origin_of] for f in OBJECTIVE_FUNCTIONS.values()
               if f.origin_of is not None}
    assert set(needing.values()) == {Kind.FRAME}
    assert {"vel", "acc", "coincident", "ic"} <= set(needing)
