"""The expression reader accepts the documented notation and refuses everything else."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechgrade.errors import ExpressionError
from mechgrade.expressions.syntax import (Attr, Call, Name, Num, Prime, constant_value, names,
                                          parse, to_text)


@pytest.mark.parametrize("text, canonical", [
    ("2 L", "2*L"),
    ("2L", "2*L"),
    ("L thetad^2", "L*thetad**2"),
    ("θ̇", "theta'"),
    ("ẍ + ÿ", "x''+y''"),
    ("ω²r", "omega**2*r"),
    ("2(x + 1)", "2*(x+1)"),
    ("(a)(b)", "a*b"),
    ("sin(x)cos(x)", "sin(x)*cos(x)"),
    ("arctan2(y, x)", "atan2(y, x)"),
    ("Abs(x)", "abs(x)"),
    ("a − b", "a-b"),
    ("a × b ÷ c", "a*b/c"),
    ("N.x + 2 A.y", "N.x+2*A.y"),
    ("-(-x)", "--x"),
    ("2**-1", "2**(-1)"),
    ("theta''", "theta''"),
])
def test_friendly_notation_is_normalised(text, canonical):
    assert to_text(parse(text)) == canonical


@pytest.mark.parametrize("text, message", [
    ("__import__('os')", "expected a prime (') only right after a name"),
    ("__import__(1)", "names may not start with '_'"),
    ("().__class__", "expected a unit vector such as N.x, found an attribute"),
    ("x.__class__", "expected a unit vector such as N.x, found 'x.__class__'"),
    ("lambda: 1", "expected names, numbers, operators and functions, found 'lambda: 1'"),
    ("x[0]", "found 'x[0]'"),
    ("x == y", "found an equation 'x == y' (write only its right-hand side)"),
    ("x if y else z", "found 'x if y else z'"),
    ('"text"', "expected a number, found a string"),
    ("True", "expected a number, found True"),
    ("9**9**9", "expected powers of at most 64, found '9**9'"),
    ("(x+1)**3000", "expected powers of at most 64, found '3000'"),
    ("1e400", "expected numbers of at most 1e+150, found 'inf' (too large)"),
    ("sin x", "expected 'sin(...)' with its argument in parentheses"),
    ("sin(x, y)", "expected 1 argument for sin(...), found 2"),
    ("f(x)", "f*x") if False else ("sin(x=1)", "expected plain arguments in 'sin(...)'"),
    ("x +", "expected a complete expression, found 'x +'"),
    ("", "expected an expression, found nothing"),
    ("x; import os", "expected a complete expression"),
    ("½", "found '½'"),
    ("x" * 3000, "expected at most 2000 characters, found 3000"),
    ("(" * 60 + "x" + ")" * 60, "nested at most 40 deep") if False else ("-" * 60 + "x", "nested at most 40 deep"),
    ("+".join(["x"] * 300), "expected an expression of at most 400 parts"),
    ("123456789012345678901234567890123", "expected a number of at most 30 digits"),
])
def test_hostile_or_broken_text_is_refused_with_a_reason(text, message):
    with pytest.raises(ExpressionError) as info:
        parse(text)
    assert message in str(info.value)


def test_attributes_can_be_refused():
    with pytest.raises(ExpressionError):
        parse("N.x", attributes=False)


def test_extra_functions_are_calls_and_unknown_ones_are_not():
    assert parse("vel(P, N)", functions=["vel"]) == Call("vel", (Name("P"), Name("N")))
    # Without the table, `vel(P, N)` is not a call: the reader refuses the tuple.
    with pytest.raises(ExpressionError):
        parse("vel(P, N)")


def test_tree_nodes():
    assert parse("theta'") == Prime("theta", 1)
    assert parse("A.y") == Attr("A", "y")
    assert parse("2.5") == Num("2.5")
    assert names(parse("a*b + sin(c)")) == {"a", "b", "c"}


def test_constant_values():
    assert constant_value(parse("2*pi")) == pytest.approx(6.283185307)
    assert constant_value(parse("x")) is None
    with pytest.raises(ExpressionError):
        constant_value(parse("1/0"))


_names = st.sampled_from(["x", "L", "theta", "omega", "r"])


def _exprs():
    leaf = st.one_of(_names, st.integers(0, 99).map(str), _names.map(lambda n: n + "'"))
    return st.recursive(leaf, lambda inner: st.one_of(
        st.tuples(inner, st.sampled_from(["+", "-", "*", "/"]), inner).map(
            lambda t: f"({t[0]}){t[1]}({t[2]})"),
        inner.map(lambda e: f"-({e})"),
        inner.map(lambda e: f"sin({e})"),
        inner.map(lambda e: f"({e})**2")), max_leaves=12)


@settings(max_examples=150)
@given(_exprs())
def test_canonical_text_reads_back_to_the_same_tree(text):
    try:
        tree = parse(text)
    except ExpressionError as err:  # constant parts such as 0/0 are refused, with a reason
        assert "divides by zero" in str(err) or "sensible size" in str(err)
        return
    assert parse(to_text(tree)) == tree


@pytest.mark.parametrize("text, message", [
    ("98.5.0", "expected an operator between two numbers, found '98.5«.0»'"),
    ("1 000", "expected an operator between two numbers, found '1 «000»'"),
    ("9.85e1.5", "expected an operator between two numbers"),
    ("x # comment", "expected an expression without '#', found 'x «#» comment'"),
    ("exp(exp(exp(100)))", "found 'exp(exp(100))' (too large)"),
    ("sqrt(-2)", "expected a real constant, found 'sqrt(-2)' (not a real number)"),
    ("log(0)", "(not a real number)"),
    ("1/0", "expected a defined constant, found '1/0' (divides by zero)"),
    ("ṥ", "expected names, numbers, operators and functions"),
])
def test_number_fragments_comments_and_bad_constants_are_refused(text, message):
    with pytest.raises(ExpressionError) as info:
        parse(text)
    assert message in info.value.message


def test_an_imaginary_literal_is_a_product_with_j():
    assert to_text(parse("3j + 2.5J")) == "3*j+2.5*J"


# ---------------------------------------------------------------------------- the fast scanner

_SCANNER_ALPHABET = "aZe_jJx019 +-*/().,"  # letters that make numbers (e, j, x), digits, operators
_PIECES = ("1", "0", "00", "1_0", "1__0", "0x1f", "0b1", "0o7", ".5", "5.", "1.5e-3", "2e", "3j",
           "1e5j", "...", "**", "//", "sqrt", "sin", "(", ")", " ", "thetad", "__d1__x", "N.x")


def _answer_forms() -> list[str]:
    """Every answer written in tests/data, and the hostile class's answers."""
    import re
    from pathlib import Path

    data = Path(__file__).resolve().parents[1] / "data"
    forms = set()
    for path in data.rglob("*"):
        if path.suffix in (".yaml", ".py", ".md"):
            text = path.read_text(encoding="utf-8", errors="replace")
            forms.update(m.group(1).strip().strip("'\"")
                         for m in re.finditer(r"answer\w*:\s*(.+)", text))
            forms.update(re.findall(r"""["']([^"'\n]{1,80})["']""", text))
    return sorted(forms)


@settings(max_examples=400)
@given(st.one_of(st.text(alphabet=_SCANNER_ALPHABET, max_size=30),
                 st.lists(st.sampled_from(_PIECES), max_size=12).map("".join)))
@pytest.mark.slow
def test_the_compiled_scanner_reads_as_pythons_tokenizer(text):
    from mechgrade.expressions.syntax import python_tokens, tokens

    def outcome(read):
        try:
            return read(text)
        except ExpressionError as exc:
            return exc.message
    assert outcome(tokens) == outcome(python_tokens)


@pytest.mark.parametrize("text", ["2 L thetad**2", "-(x + r*thetad*sin(theta))/17",
                                  "sqrt(xd**2 + yd**2)", "1.5e-3 .5 N.x", "a ... b // c"])
def test_plain_answers_are_read_by_the_compiled_scanner(text, monkeypatch):
    from mechgrade.expressions import syntax

    def refuse(text):
        raise AssertionError("read by tokenize")
    monkeypatch.setattr(syntax, "python_tokens", refuse)
    assert syntax.tokens(text)


@pytest.mark.parametrize("text", _answer_forms())
def test_every_answer_form_normalises_as_with_pythons_tokenizer(text, monkeypatch):
    from mechgrade.expressions import syntax

    def outcome():
        try:
            return syntax.normalize(text, ("vel",))
        except ExpressionError as exc:
            return exc.message
    fast = outcome()
    monkeypatch.setattr(syntax, "_scan", lambda text: None)  # tokenize reads every text
    assert fast == outcome()


# ------------------------------------------- issue 18: what a student typed, as they meant it


@pytest.mark.parametrize("text, canonical", [
    ("ζωt", "zeta*omega*t"),
    ("mω²r", "m*omega**2*r"),
    ("2π√(L/g)", "2*pi*sqrt(L/g)"),
    ("√2/2", "sqrt(2)/2"),
    ("-√3 L", "-sqrt(3)*L"),
    ("√θ", "sqrt(theta)"),
    ("θd + θ1 + ω_A + θdot + θ_dot", "thetad+theta1+omega_A+thetadot+theta_dot"),
    ("sin(30°)", "sin(30*pi/180)"),
    ("sin(30 deg) + cos(1.5e1degrees)", "sin(30*pi/180)+cos(15.0*pi/180)"),
    ("1/2 m v^2", "1/2*m*v**2"),
    ("g/L sin(theta)", "g/L*sin(theta)"),
    ("3*g/2*L", "3*g/2*L"),
    ("a/2**3 b", "a/2**3*b"),
    ("2pisqrt(L/g) + Lcos(theta)", "2*pi*sqrt(L/g)+L*cos(theta)"),
    ("x_sign(2) + x_(1)", "x_sign*2+x_*1"),
])
def test_greek_letters_roots_and_degrees_read_as_written(text, canonical):
    assert to_text(parse(text)) == canonical


@pytest.mark.parametrize("text, message", [
    # WeBWorK binds juxtaposition tighter than '/', STACK and sympy do not: ask
    ("3g/2L", "expected brackets to show what is divided, found '3g/2L': 3g/(2L) or "
              "(3g/2)L?"),
    ("v^2/2g", "found 'v^2/2g': v^2/(2g) or (v^2/2)g?"),
    ("a + 1/2x", "found '1/2x': 1/(2x) or (1/2)x?"),
    ("x/y(1 + x)", "found 'x/y(1 + x)': x/(y(1 + x)) or (x/y)(1 + x)?"),
    ("(a/b^2c)", "found 'a/b^2c': a/(b^2c) or (a/b^2)c?"),
    ("θ̇/2L", "found 'theta'/2L': theta'/(2L) or (theta'/2)L?"),
    ("√2gh", "expected brackets after √, found '√2gh': √(2gh) or √(2)gh?"),
    ("√x^2", "expected brackets after √, found '√x^2': √(x^2) or √(x)^2?"),
    ("√", "expected a number, a name or brackets after √, found nothing"),
])
def test_ambiguous_products_and_roots_are_refused_with_both_readings(text, message):
    with pytest.raises(ExpressionError) as info:
        parse(text)
    assert message in info.value.message


# ---------------------------------------------------------------------------- the fast reader

_READER_PIECES = ("1", "0", "2.5", "1e3", "007", "0x1f", "1_0", "x", "L", "N.x", "N.y.z", "True",
                  "theta'", "sqrt(", "atan2(", "sin(", "vel(", "(", ")", ",", "+", "-", "*", "/",
                  "**", "//", "%", "==", "9**9", "2**-1", "-", "pi", "lambda", ".", "_x", "e", "3j",
                  "Lcos(", "2L")


def _outcome(read):
    try:
        return read()
    except ExpressionError as exc:
        return exc.message


@settings(max_examples=600)
@given(st.one_of(st.lists(st.sampled_from(_READER_PIECES), max_size=14).map(" ".join),
                 st.lists(st.sampled_from(_READER_PIECES), max_size=14).map("".join), _exprs()))
def test_the_fast_reader_reads_as_ast(text):
    from mechgrade.expressions import syntax

    names = syntax._function_names(("vel",))
    for attributes in (True, False):
        def by_ast(attributes=attributes):
            tree = syntax._read_by_ast(text, syntax._pieces(text, names)[0], names,
                                       attributes)
            ambiguous = syntax._pieces(text, names)[1]
            if ambiguous is not None:
                raise ambiguous
            return tree
        assert _outcome(lambda attributes=attributes: parse(text, functions=("vel",),
                                                           attributes=attributes)) \
            == _outcome(by_ast)


@pytest.mark.parametrize("text", ["2 L thetad**2", "-(x + r*thetad*sin(theta))/17",
                                  "sqrt(xd**2 + yd**2)", "-x**2 + 2**-1", "3 N.x - atan2(1, 2)",
                                  "L*sqrt(thetad**4 + thetadd**2)", "theta'' + 2.5e-3",
                                  "1/2 m v^2", "-3 g sin(theta)/(2 L)", "g/L sin(theta)(2)"])
def test_plain_answers_are_read_in_one_pass(text, monkeypatch):
    from mechgrade.expressions import syntax

    expected = parse(text)
    for name in ("_implicit_products", "python_tokens"):
        monkeypatch.setattr(syntax, name, lambda *a, name=name: (_ for _ in ()).throw(
            AssertionError(f"read by {name}")))
    monkeypatch.setattr(syntax.ast, "parse", lambda *a, **k: (_ for _ in ()).throw(
        AssertionError("read by ast")))
    assert parse(text) == expected
