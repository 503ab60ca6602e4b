"""Read expression text into a small syntax tree, without ever calling ``eval``.

The same reader serves problem specs and student answers. Text is normalised (Unicode NFC,
Greek letters to names, superscripts, ``^`` for powers, dot accents and primes for time
derivatives, implicit multiplication), parsed with :func:`ast.parse` in ``eval`` mode, and every
node is checked against an allow-list: numbers, names, ``Frame.x`` unit vectors, ``+ - * / **``,
unary minus and calls to a fixed table of functions. Size, depth, literal and exponent bounds are
enforced here, before sympy does any arithmetic.

>>> parse("2 L θ̇^2")
Bin(op='*', left=Bin(op='*', left=Num(text='2'), right=Name(id='L')), right=Bin(op='**', left=Prime(id='theta', order=1), right=Num(text='2')))
>>> parse("__import__(1)")
Traceback (most recent call last):
...
mechgrade.errors.ExpressionError: expected names, numbers, operators and functions, found '__import__' (names may not start with '_')
"""

from __future__ import annotations

import ast
import io
import keyword
import math
import operator
import re
import tokenize
import unicodedata
from dataclasses import dataclass
from typing import ClassVar, Iterable, Union

from ..errors import ExpressionError
from . import functions
from .excerpt import excerpt

MAX_LENGTH = 2000
MAX_NODES = 400
MAX_DEPTH = 40
MAX_LITERAL_DIGITS = 30
MAX_POWER = 64
MAX_MAGNITUDE = 1e150
TOO_MANY_PARTS = f"expected an expression of at most {MAX_NODES} parts"

# Every spelling of a math function -> (canonical name, arity): a view of the one table.
MATH_FUNCTIONS: dict[str, tuple[str, int]] = {
    written: (f.name, f.arity) for f in functions.MATH_FUNCTIONS.values()
    for written in (f.name, *f.aliases)}

GREEK = {
    "α": "alpha", "β": "beta", "γ": "gamma", "δ": "delta", "ε": "epsilon", "ϵ": "epsilon",
    "ζ": "zeta", "η": "eta", "θ": "theta", "ϑ": "theta", "ι": "iota", "κ": "kappa",
    "λ": "lambda_", "μ": "mu", "ν": "nu", "ξ": "xi", "π": "pi", "ρ": "rho", "σ": "sigma",
    "τ": "tau", "υ": "upsilon", "φ": "phi", "ϕ": "phi", "χ": "chi", "ψ": "psi", "ω": "omega",
    "Γ": "Gamma", "Δ": "Delta", "Θ": "Theta", "Λ": "Lambda", "Ξ": "Xi", "Π": "Pi",
    "Σ": "Sigma", "Φ": "Phi", "Ψ": "Psi", "Ω": "Omega",
}
_SYMBOL_CHARS = {
    "−": "-", "–": "-", "×": "*", "·": "*", "⋅": "*", "∙": "*", "÷": "/", "√": "sqrt",
    "²": "^2", "³": "^3", "⁴": "^4", "¹": "^1", "⁰": "^0", "⁻¹": "^-1", "⁻²": "^-2",
    "′": "'", "″": "''", "’": "'",
}
_COMBINING_DOT = "\u0307"
_COMBINING_DIAERESIS = "\u0308"
_PRIME = re.compile(r"([A-Za-z][A-Za-z0-9_]*)('{1,2})")


# ---------------------------------------------------------------------------- syntax tree


@dataclass(frozen=True)
class Num:
    """A number literal, kept as written so it can be made exact or float later."""

    text: str

    @property
    def value(self) -> float:
        return float(self.text)


@dataclass(frozen=True)
class Name:
    id: str


@dataclass(frozen=True)
class Prime:
    """The ``order``-th time derivative of the quantity ``id`` (``theta'``, ``θ̈``)."""

    id: str
    order: int


@dataclass(frozen=True)
class Attr:
    """``base.attr``: a unit vector of a frame, such as ``N.x``."""

    base: str
    attr: str


@dataclass(frozen=True)
class Unary:
    op: str
    operand: "Node"


@dataclass(frozen=True)
class Bin:
    op: str
    left: "Node"
    right: "Node"


@dataclass(frozen=True)
class Call:
    func: str
    args: tuple["Node", ...]


Node = Union[Num, Name, Prime, Attr, Unary, Bin, Call]


def walk(node: Node) -> Iterable[Node]:
    """Every node of the tree, parents first.

    >>> [type(n).__name__ for n in walk(parse("-a*b"))]
    ['Bin', 'Unary', 'Name', 'Name']
    """
    yield node
    if isinstance(node, Unary):
        yield from walk(node.operand)
    elif isinstance(node, Bin):
        yield from walk(node.left)
        yield from walk(node.right)
    elif isinstance(node, Call):
        for arg in node.args:
            yield from walk(arg)


def names(node: Node) -> set[str]:
    """The plain names used in an expression (not function names, not frames of unit vectors)."""
    return {n.id for n in walk(node) if isinstance(n, Name)}


def name_of(node: Node) -> str:
    """The name written where the language allows only a name (a frame, body or point
    argument); the spec checks make sure of it before any solver reads the argument.

    >>> name_of(Call("vel", (Name("P"), Name("N"))).args[1])
    'N'
    """
    assert isinstance(node, Name), node
    return node.id


def to_text(node: Node, *, spaced: bool = False) -> str:
    """Canonical text for a tree (fully parenthesised where needed; parses back to the same
    tree); ``spaced``: with spaces around binary ``+`` and ``-``, as an answer is read back.

    >>> to_text(parse("2 L θ̇^2"))
    "2*L*theta'**2"
    >>> to_text(parse("a-(-b)+1e-5*c"), spaced=True)
    'a - -b + 1e-05*c'
    """
    return _text(node, 0, " " if spaced else "")


_PRECEDENCE = {"+": 1, "-": 1, "*": 2, "/": 2, "u": 3, "**": 4}


def _text(node: Node, parent: int, space: str) -> str:
    # the commonest kinds first, told by their exact type (every answer read is written back)
    if type(node) is Bin:
        prec = _PRECEDENCE[node.op]
        if node.op == "**":
            out = f"{_text(node.left, prec + 1, space)}**{_text(node.right, prec, space)}"
        else:
            op = f"{space}{node.op}{space}" if prec == 1 else node.op
            out = f"{_text(node.left, prec, space)}{op}{_text(node.right, prec + 1, space)}"
        return f"({out})" if parent > prec else out
    if type(node) is Name:
        return node.id
    if type(node) is Num:
        return node.text
    if isinstance(node, Prime):
        return node.id + "'" * node.order
    if isinstance(node, Attr):
        return f"{node.base}.{node.attr}"
    if isinstance(node, Call):
        return f"{node.func}({', '.join(_text(a, 0, space) for a in node.args)})"
    assert isinstance(node, Unary)
    out = node.op + _text(node.operand, _PRECEDENCE["u"], space)
    return f"({out})" if parent > _PRECEDENCE["u"] else out


# ---------------------------------------------------------------------------- normalising


def normalize(text: str, functions: Iterable[str] = ()) -> str:
    """Rewrite friendly notation into the Python-like syntax the reader parses.

    ``functions`` are extra function names (besides the math table) after which ``(`` opens
    a call rather than an implicit product.

    >>> normalize("½ω²r")
    Traceback (most recent call last):
    ...
    mechgrade.errors.ExpressionError: expected names, numbers, operators and functions, found '½'
    >>> normalize("2 L θ̇^2 + ẍ")
    '2 * L * __d1__theta ** 2 + __d2__x'
    """
    return _normalized(text, _function_names(functions))


def _function_names(functions: Iterable[str]) -> frozenset[str] | set[str]:
    functions = tuple(functions)
    return _MATH_NAMES | set(functions) if functions else _MATH_NAMES


def _normalized(text: str, functions: frozenset[str] | set[str]) -> str:
    pieces, ambiguous = _pieces(text, functions)
    if ambiguous is not None:
        raise ambiguous
    return " ".join(string for _, string in pieces)


def _pieces(text: str, functions: frozenset[str] | set[str]
            ) -> tuple[list[Piece], ExpressionError | None]:
    """The normalised tokens of ``text``, implicit products written out, and the refusal
    of an ambiguous product (see :func:`_implicit_products`)."""
    return _implicit_products(_prepared(text), functions)


def _prepared(text: str) -> str:
    """``text`` checked (type, length, no ``#``) and rewritten as far as it can be before
    it is read: Unicode, degrees, ``^`` and primes."""
    if not isinstance(text, str):
        raise ExpressionError(f"expected text, found {type(text).__name__}")
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"expected at most {MAX_LENGTH} characters, found {len(text)}")
    if "#" in text:  # Python's tokenizer would drop the rest as a comment
        raise ExpressionError(f"expected an expression without '#', found "
                              f"{excerpt(text, text.index('#'))}")
    if not text.isascii():  # plain ASCII is its own NFC form, with no letters to rewrite
        text = _rewrite_unicode(text)
    if "deg" in text:
        text = _DEGREES.sub(_in_degrees, text)
    text = text.replace("^", "**")
    if "'" in text:  # only then can there be a rate to rewrite
        text = _PRIME.sub(lambda m: f" __d{len(m.group(2))}__{m.group(1)}", text)
        if "'" in text:
            raise ExpressionError("expected a prime (') only right after a name, as in theta'")
    return text


def _rewrite_unicode(text: str) -> str:
    """Greek letters to names, symbols to operators, dot accents to primes (NFC first).

    A Greek letter is one symbol however it is spelled out: its name is kept apart from the
    letters around it (``ζωt`` is ``zeta omega t``), except a derivative suffix (``θd``,
    ``θdot``), a digit or an underscore after it (``θ1``, ``ω_A``). ``√`` takes the number,
    name or brackets after it (:func:`_roots`); ``°`` after a number is degrees.
    """
    text = unicodedata.normalize("NFC", text)
    out: list[str] = []
    greek = False  # whether the last piece written was a Greek letter's name
    for at, ch in enumerate(text):
        decomposed = unicodedata.normalize("NFD", ch)
        accent = ""
        if len(decomposed) > 1 and decomposed[-1] in (_COMBINING_DOT, _COMBINING_DIAERESIS):
            accent = "'" if decomposed[-1] == _COMBINING_DOT else "''"
            ch = decomposed[:-1]
        if ch == _COMBINING_DOT:
            out.append("'")
            continue
        if ch == _COMBINING_DIAERESIS:
            out.append("''")
            continue
        if len(ch) != 1:  # several accents on one letter (ṥ): not a derivative we read
            raise ExpressionError(f"expected names, numbers, operators and functions, "
                                  f"found {excerpt(decomposed)}")
        if ch in GREEK:
            if out and (out[-1][-1:].isalnum() or greek):
                out.append(" ")
            out.append(GREEK[ch] + accent)
            greek = True
            continue
        if greek and ch.isascii() and ch.isalpha() and not _RATE_SUFFIX.match(text, at):
            out.append(" ")
        greek = False
        if ch == "√":
            ch = " √"
        elif ch == "°":
            ch = " deg "
        elif ch in _SYMBOL_CHARS:
            ch = _SYMBOL_CHARS[ch]
        elif ord(ch) > 127 and not ch.isspace():
            raise ExpressionError(
                f"expected names, numbers, operators and functions, found {ch!r}")
        out.append(ch + accent)
    return _roots("".join(out))


def _in_degrees(m: re.Match) -> str:
    """``30°`` or ``30 deg`` inside brackets (``sin(30°)``) as ``(30*pi/180)``; outside them
    ``deg`` stays a unit (``2*30 deg`` is 60 degrees with its unit)."""
    before = m.string[:m.start()]
    if before.count("(") <= before.count(")"):
        return m.group(0)
    return f"({m.group(1)}*pi/180)"


_RATE_SUFFIX = re.compile(r"(?:d|dd|dot|ddot)(?![A-Za-z])")
_DEGREES = re.compile(r"(?<![\w.])((?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*deg(?:rees?)?(?!\w)")
_ROOT = re.compile(r"√\s*(?:(?P<open>\()|(?P<atom>(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"
                   r"|[A-Za-z_][A-Za-z0-9_]*'*))?")
# what would make the extent of a root unclear: a power, or more glued to its operand
_AFTER_ROOT = re.compile(r"(?:(?:\^|\*\*)[+-]?)?(?:\(|[^\s+\-*/^(),=]*)")


def _roots(text: str) -> str:
    """``√`` as ``sqrt``: ``√(L/g)``, or the one number or name after it (``√2/2``, ``√θ``).

    A number or name glued to more (``√2gh``) or raised to a power (``√x^2``) could be under
    the root or not: refused with both readings.

    >>> _roots("2 pi √(L/g) + √2/2")
    '2 pi sqrt(L/g) + sqrt(2)/2'
    """
    def root(m: re.Match) -> str:
        atom = m.group("atom")
        if m.group("open"):
            return "sqrt("
        if atom is None:
            rest = m.string[m.end():].strip()
            raise ExpressionError("expected a number, a name or brackets after √, found "
                                  + (excerpt(rest) if rest else "nothing"))
        after = _AFTER_ROOT.match(m.string, m.end())
        assert after is not None  # every part of the pattern may be empty
        more = after.group(0)
        if more.endswith("("):  # a power in brackets: up to its closing bracket
            depth, start = 0, m.end() + len(more) - 1
            for end in range(start, len(m.string)):
                depth += {"(": 1, ")": -1}.get(m.string[end], 0)
                if depth == 0:
                    break
            more = m.string[m.end():end + 1]
        if not more:
            return f"sqrt({atom})"
        said = (f": √({atom}{more}) or √({atom}){more}?" if len(atom + more) <= 24
                else " (what is under the root?)")
        raise ExpressionError(f"{AMBIGUOUS} after √, found {excerpt('√' + atom + more)}{said}")
    return _ROOT.sub(root, text)


Token = tuple[int, str, int, int]
"""A token as Python's tokenizer reads it: type (``tokenize.NAME``...), text, start and end
column."""

_SIMPLE = re.compile(r"[A-Za-z0-9_ +\-*/().,]*")
# The spaces before a token, then the token: a name (most tokens are), an operator (a "."
# before a digit starts a number) or a number, by tokenize's own pattern (its groups made
# non-capturing, so findall gives these four), whose many alternatives are the slowest to try:
# a whole number that nothing of a longer literal follows (most numbers) is taken first, as
# that pattern would take it.
_SCAN = re.compile(r"( *)(?:([A-Za-z_][A-Za-z0-9_]*)|(\*\*|\*|//|/|\.\.\.|\.(?![0-9])|[-+(),])"
                   r"|((?:[1-9][0-9]*|0)(?![0-9_.eEjJxXoObB])|"
                   + re.sub(r"\((?!\?)", "(?:", tokenize.Number) + r"))")


def tokens(text: str) -> list[Token]:
    """The tokens of one line of normalised text, as :mod:`tokenize` reads them (without its
    line structure: no NEWLINE, INDENT or ENDMARKER).

    Text made only of names, numbers, spaces and ``+ - * / ( ) , .`` with balanced
    parentheses (nearly every answer) is read by one compiled pattern built on tokenize's own
    number pattern; anything else goes through :mod:`tokenize` itself, which also words the
    errors. The tests prove both readings agree.

    >>> tokens("2L (x)")
    [(2, '2', 0, 1), (1, 'L', 1, 2), (54, '(', 3, 4), (1, 'x', 4, 5), (54, ')', 5, 6)]
    """
    if _SIMPLE.fullmatch(text):
        scanned = _scan(text)
        if scanned is not None:
            return scanned
    return python_tokens(text)


def _scan(text: str) -> list[Token] | None:
    """``text`` (only characters of :data:`_SIMPLE`) read with :data:`_SCAN`; ``None`` when
    its parentheses do not balance (tokenize then says how). Every character of
    :data:`_SIMPLE` starts a token or is a space before one, so the matches follow one another
    (only trailing spaces are left over) and each token starts where the last one ended, after
    its spaces."""
    out: list[Token] = []
    depth = 0
    end = 0
    for spaces, name, op, number in _SCAN.findall(text):
        start = end + len(spaces)
        if name:
            end = start + len(name)
            out.append((tokenize.NAME, name, start, end))
            continue
        if op == "(":
            depth += 1
        elif op == ")":
            depth -= 1
            if depth < 0:
                return None
        string = op or number
        end = start + len(string)
        out.append((tokenize.OP if op else tokenize.NUMBER, string, start, end))
    return out if depth == 0 else None


def python_tokens(text: str) -> list[Token]:
    """The tokens of ``text`` read by :mod:`tokenize` (any text; see :func:`tokens`)."""
    try:
        return [(t.type, t.string, t.start[1], t.end[1])
                for t in tokenize.generate_tokens(io.StringIO(text).readline)
                if t.type not in (tokenize.NEWLINE, tokenize.NL, tokenize.ENDMARKER,
                                  tokenize.INDENT, tokenize.DEDENT)]
    except (tokenize.TokenError, IndentationError, SyntaxError) as exc:
        raise ExpressionError(f"expected a complete expression, found {excerpt(text)} "
                              f"({_reason(exc)})") from None


Piece = tuple[int, str]
"""A normalised token: its type (``tokenize.NUMBER``...) and text."""


def _implicit_products(text: str, functions: frozenset[str] | set[str]
                       ) -> tuple[list[Piece], ExpressionError | None]:
    """The pieces, and the refusal of a divisor glued to a product (:class:`_Divisors`)
    for when the text reads otherwise."""
    pieces: list[Piece] = []
    # the last token that is not stray whitespace: whether it ends an operand, whether it is
    # a number, and whether a "(" after it opens a call
    ends = number = calls = False
    found = tokens(text)
    # only a text with a "/" can have a divisor glued to a product
    divisors = _Divisors(text, found) if "/" in text else None
    for index, (kind, string, start, end) in enumerate(found):
        if kind == tokenize.ERRORTOKEN:
            if not string.isspace():
                raise ExpressionError(f"expected names, numbers, operators and functions, "
                                      f"found {excerpt(string)}")
            pieces.append((kind, string))
            continue
        if kind == tokenize.NUMBER:
            if number:
                # "98.5.0", "1 000", "9.85e1.5": never read number fragments as a product
                raise ExpressionError(f"expected an operator between two numbers, found "
                                      f"{excerpt(text, start, end)}")
            if ends:
                if divisors:
                    divisors.product(index)
                pieces.append(_TIMES)
            if string[-1] in "jJ":
                # Python's imaginary literal: "3j" is 3 times the name j
                if divisors:
                    divisors.glued_j(index)
                pieces += [(kind, string[:-1]), _TIMES, (tokenize.NAME, string[-1])]
            else:
                pieces.append((kind, string))
            ends, number, calls = True, True, False
        elif kind == tokenize.NAME:
            is_keyword = string in _KEYWORDS
            if ends and not is_keyword:
                if divisors:
                    divisors.product(index)
                pieces.append(_TIMES)
            # only a bracket right after a name can make it a name and a call
            glued = _glued_call(string, functions) if index + 1 < len(found) \
                and found[index + 1][1] == "(" and found[index + 1][2] == end else None
            if glued:  # "pisqrt(L/g)", "Lcos(theta)": a name, then a call
                pieces += [(kind, string[:-len(glued)]), _TIMES]
                string = glued
            pieces.append((kind, string))
            ends, number, calls = not is_keyword, False, string in functions
        else:
            if string == "(" and ends and not calls:
                if divisors:
                    divisors.product(index)
                pieces.append(_TIMES)
            if divisors:
                divisors.operator(index, binary=ends)
            pieces.append((kind, string))
            ends, number, calls = string == ")", False, False
            continue
        if divisors:
            divisors.operand(index)
    return pieces, divisors.ambiguous if divisors else None


_TIMES: Piece = (tokenize.OP, "*")


def _glued_call(name: str, functions: frozenset[str] | set[str]) -> str | None:
    """The function a name not itself a function ends with, for a name a bracket follows
    directly (``pisqrt(`` is ``pi*sqrt(``); the longest such name."""
    if name in functions:
        return None
    ends_with = [f for f in functions if name.endswith(f) and len(f) < len(name)]
    if not ends_with:
        return None
    glued = max(ends_with, key=len)
    prefix = name[:-len(glued)]
    # x_sign(...) is a name, then a product: an underscore joins the parts of one name
    return glued if prefix.isidentifier() and "_" not in (prefix[0], prefix[-1]) else None


class _Divisors:
    """Where a product written by juxtaposition follows a divisor (``3g/2L``, ``v^2/2g``).

    WeBWorK binds juxtaposition tighter than ``/`` (3g/(2L)); STACK, sympy and Python read
    left to right ((3g/2)L). A juxtaposition glued to the divisor (no space) is refused with
    both readings; one after a space (``1/2 m v^2``) or an explicit ``*`` is read left to
    right. Each level of brackets has its own term: ``term`` holds, per depth, where it
    started, and ``slash`` where its divisor's ``/`` is while the divisor is being read."""

    def __init__(self, text: str, found: list[Token]):
        self.text, self.found = text, found
        self.depth = 0
        self.term: dict[int, int | None] = {0: None}
        self.slash: dict[int, tuple[int, int]] = {}
        self.last_end = -1
        # the first such product: refused once the text reads otherwise (a reason about the
        # brackets of text that cannot be read anyway would mislead)
        self.ambiguous: ExpressionError | None = None

    def operand(self, index: int) -> None:
        """A number or name: the term starts here if nothing of it came before."""
        _, _, start, end = self.found[index]
        if self.term.get(self.depth) is None:
            self.term[self.depth] = start
        self.last_end = end

    def product(self, index: int) -> None:
        """A juxtaposition before token ``index``: after a space it ends the divisor."""
        slash = self.slash.pop(self.depth, None)
        start = self.found[index][2]
        if slash is not None and start == self.last_end and self.ambiguous is None:
            self.ambiguous = self._ambiguous(slash, start, index)

    def glued_j(self, index: int) -> None:
        slash = self.slash.get(self.depth)
        if slash is not None and self.ambiguous is None:
            self.ambiguous = self._ambiguous(slash, self.found[index][3] - 1, index)

    def operator(self, index: int, binary: bool) -> None:
        _, string, start, end = self.found[index]
        if string in ("(", ")") or (string in "+-" and not binary):
            # brackets and a sign belong to the term
            if self.term.get(self.depth) is None:
                self.term[self.depth] = start
        if string == "(":
            self.depth += 1
            self.term[self.depth] = None
            self.slash.pop(self.depth, None)
        elif string == ")":
            self.slash.pop(self.depth, None)
            self.depth -= 1
        elif string == "/":
            self.slash[self.depth] = (start, self.term.get(self.depth) or 0)
        elif string in ("*", "//", ",") or (string in "+-" and binary):
            self.slash.pop(self.depth, None)
            if string != "*":
                self.term[self.depth] = None
        self.last_end = end

    def _ambiguous(self, slash: tuple[int, int], start: int, index: int) -> ExpressionError:
        """The refusal, with the term read both ways."""
        at, term = slash
        depth, stop = 0, len(self.text)
        for _, string, begin, _ in self.found[index:]:  # the glued factor runs to an operator
            if depth == 0 and (string in ("+", "-", "*", "/", ",", ")")):
                stop = begin
                break
            depth += (string == "(") - (string == ")")
        shown = [_shown(self.text[a:b]).strip()
                 for a, b in ((term, at), (at + 1, start), (start, stop))]
        numerator, divisor, factor = shown
        readings = (f"{numerator}/({divisor}{factor})", f"({numerator}/{divisor}){factor}")
        said = (f": {readings[0]} or {readings[1]}?" if max(map(len, readings)) <= 32
                else " (put brackets around what is divided)")
        return ExpressionError(f"{AMBIGUOUS} to show what is divided, found "
                               f"{excerpt(_shown(self.text[term:stop]).strip())}{said}")


def _shown(text: str) -> str:
    """Normalised text as the writer would recognise it: ``^`` and primes again."""
    text = re.sub(r"\s*\*\*\s*", "^", text)
    return re.sub(r" ?__d([12])__([A-Za-z][A-Za-z0-9_]*)",
                  lambda m: m.group(2) + "'" * int(m.group(1)), text)


_KEYWORDS = {"and", "or", "not", "in", "is", "if", "else", "lambda", "for"}


def _reason(exc: BaseException) -> str:
    msg = exc.args[0] if exc.args else str(exc)
    return str(msg).split("(")[0].strip()


# ---------------------------------------------------------------------------- parsing


def parse(text: str, *, functions: Iterable[str] = (), attributes: bool = True) -> Node:
    """Read ``text`` into a syntax tree, or raise :class:`ExpressionError` saying why not.

    ``functions``: extra allowed function names (for example the kinematics functions of the
    spec language); ``attributes``: whether ``Frame.x`` unit vectors are allowed.

    >>> parse("sqrt(xd**2 + yd**2)")
    Call(func='sqrt', args=(Bin(op='+', left=Bin(op='**', left=Name(id='xd'), right=Num(text='2')), right=Bin(op='**', left=Name(id='yd'), right=Num(text='2'))),))
    """
    names = _function_names(functions)
    prepared = _prepared(text)
    read = _Reader(prepared, names, attributes).read() if _SIMPLE.fullmatch(prepared) else None
    if read is None:
        pieces, ambiguous = _implicit_products(prepared, names)
        read = _read_by_ast(text, pieces, names, attributes)
        if ambiguous is not None:
            raise ambiguous
    return read


def _read_by_ast(text: str, pieces: list[Piece], names: frozenset[str] | set[str],
                 attributes: bool) -> Node:
    """The pieces read by :func:`ast.parse` and checked by :class:`_Builder` (any text)."""
    source = " ".join(string for _, string in pieces)
    if not source.strip():
        raise ExpressionError("expected an expression, found nothing")
    try:
        tree = ast.parse(source.strip(), mode="eval")
    except SyntaxError as exc:
        raise ExpressionError(f"expected a complete expression, found {excerpt(text.strip())} "
                              f"({_reason(exc)})", offset=exc.offset) from None
    except (MemoryError, RecursionError, ValueError):
        raise ExpressionError("expected a simpler expression (too deeply nested)") from None
    return _Builder(names, attributes).build(tree.body, 0)[0]


_MATH_NAMES = frozenset(MATH_FUNCTIONS)
_RATE_NAME = re.compile(r"__d([12])__([A-Za-z][A-Za-z0-9_]*)")

Built = tuple["Node", Union[float, None]]
"""A tree and its constant value (:func:`constant_value`; ``None`` when it uses a name)."""


class _Unread(Exception):
    """Text the fast reader leaves to :mod:`ast` (anything unusual, and every refusal)."""


class _Reader:
    """The tree :class:`_Builder` makes of ``ast.parse``'s, read in one pass over the
    prepared text (:func:`_prepared`): its tokens, the products written by juxtaposition and
    the tree together.

    Text made of :data:`_SIMPLE`'s characters only, in Python's grammar restricted to what
    answers are made of: numbers written plainly, names, ``N.x``, calls of known functions,
    brackets, unary minus, ``+ - * / **`` with Python's precedence (``-x**2`` is ``-(x**2)``;
    ``**`` binds to the right and takes a sign on its right) and a product written by
    juxtaposition wherever :func:`_implicit_products` writes one out (before a number, a name
    or a bracket that follows an operand). The same checks on every part (:class:`_Builder`'s
    own), and the same bounds on size and nesting, counted as it counts them. Anything else,
    every refusal and every text :func:`_implicit_products` would refuse or find ambiguous (a
    product glued to a divisor, a name glued to a call, two numbers in a row) is left to
    :func:`_implicit_products` and ``ast`` (:meth:`read` returns ``None``), so a reason is
    worded once. The tests prove both readings agree; this one only saves their cost (most
    of reading an answer).

    Each part is read as ``(node, constant value, height)``: the height is how deep
    :class:`_Builder` would find the part's deepest node below it (a flat chain ``a + b + c``
    is one level, as it counts). A token is :data:`_SCAN`'s: spaces before it, then its text
    as a name, an operator or a number (the other two empty).
    """

    MAX_TOKENS = 160
    """Longer texts are left to ``ast`` (bounds are then checked as the text is built)."""

    def __init__(self, text: str, functions: frozenset[str] | set[str], attributes: bool):
        self.tokens: list[tuple[str, str, str, str]] = _SCAN.findall(text)
        self.tokens.append(_END)
        self.at = 0
        self.builder = _Builder(functions, attributes)
        self.nesting = 0
        self.count = 0
        # the brackets' depth, and the depths where a divisor is being read: a product glued
        # to it is ambiguous (see :class:`_Divisors`); None when the text divides nowhere
        self.depth = 0
        self.divisors: set[int] | None = set() if "/" in text else None

    def read(self) -> Node | None:
        if len(self.tokens) == 1 or len(self.tokens) > self.MAX_TOKENS:
            return None
        try:
            node, _, height = self.sum()
        except (_Unread, ExpressionError):
            return None
        if self.at != len(self.tokens) - 1 or self.count > MAX_NODES or height > MAX_DEPTH:
            return None
        return node

    def take(self) -> tuple[str, str, str, str]:
        token = self.tokens[self.at]
        if token is _END:
            raise _Unread
        self.at += 1
        return token

    def sum(self) -> _Read:
        left = self.product()
        while (op := self.tokens[self.at][2]) in ("+", "-"):
            self.at += 1
            self.term_ends()
            left = self.binary(op, left, self.product())
        return left

    def product(self) -> _Read:
        left = self.signed()
        while True:
            spaces, name, op, number = self.tokens[self.at]
            if op == "*" or op == "/":
                self.at += 1
                if op == "*":
                    self.term_ends()
                elif self.divisors is not None:
                    self.divisors.add(self.depth)
            elif name or number or op == "(":  # a product written by juxtaposition
                if number and self.tokens[self.at - 1][3]:
                    raise _Unread  # two numbers: refused by _implicit_products
                if self.divisors is not None and self.depth in self.divisors:
                    self.divisors.discard(self.depth)
                    if not spaces:
                        raise _Unread  # glued to a divisor: ambiguous
                op = "*"
            else:
                return left
            left = self.binary(op, left, self.signed())

    def signed(self) -> _Read:
        op = self.tokens[self.at][2]
        if op == "-":
            self.take()
            self.nest()
            operand, value, height = self.signed()
            self.nesting -= 1
            self.count += 1
            return Unary("-", operand), None if value is None else -value, height + 1
        if op == "+":
            raise _Unread  # ast keeps a node for it, and so counts it
        # the power, read here: every operand passes this way (one call fewer each)
        base = self.atom()
        if self.tokens[self.at][2] == "**":
            self.take()
            return self.binary("**", base, self.signed())
        return base

    def binary(self, op: str, left: _Read, right: _Read) -> _Read:
        (a_node, a, a_height), (b_node, b, b_height) = left, right
        self.count += 1
        if not (type(a_node) is Bin and op != "**"):  # a chain's left part counts no level
            a_height += 1
        b_height += 1
        node, value = _combined(op, (a_node, a), (b_node, b))
        return node, value, a_height if a_height > b_height else b_height

    def nest(self) -> None:
        self.nesting += 1
        if self.nesting > MAX_DEPTH:
            raise _Unread

    def term_ends(self) -> None:
        """An operator that ends the divisor being read at this depth (``*``, ``,``, a
        binary sign)."""
        if self.divisors is not None:
            self.divisors.discard(self.depth)

    def opened(self) -> None:
        self.nest()
        self.depth += 1
        if self.divisors is not None:
            self.divisors.discard(self.depth)

    def closed(self) -> None:
        if self.take()[2] != ")":
            raise _Unread
        self.term_ends()
        self.depth -= 1
        self.nesting -= 1

    def atom(self) -> _Read:
        token = self.tokens[self.at]  # take(), written in: every operand is an atom
        if token is _END:
            raise _Unread
        self.at += 1
        _, name, op, number = token
        if number:
            if number.isascii() and number.isdigit() and (number[0] != "0" or len(number) == 1) \
                    and len(number) <= MAX_LITERAL_DIGITS:
                built = Num(number)  # most numbers: plain integers, written as _number writes them
            elif not _PLAIN_NUMBER.fullmatch(number):
                raise _Unread  # 0x1f, 1_000, 007, 3j: Python's own literals
            else:
                built = self.builder._number(float(number) if _FLOAT.search(number)
                                             else int(number))
            self.count += 1
            return built, built.value, 0
        if name:
            if keyword.iskeyword(name):  # True, None, lambda...: Python's, not names
                raise _Unread
            spaces, _, after, _ = self.tokens[self.at]
            if after == "(":
                if name in self.builder.functions:
                    return self.call(name)
                if not spaces and _glued_call(name, self.builder.functions):
                    raise _Unread  # "Lcos(theta)": a name, then a call
            self.count += 1
            if after == ".":
                self.take()
                attr = self.take()[1]
                base = self.builder._name(name)
                if not self.builder.attributes or not isinstance(base, Name) \
                        or attr not in ("x", "y", "z") or self.tokens[self.at][2] in (".", "("):
                    raise _Unread
                return Attr(base.id, attr), None, 0
            leaf = self.builder._name(name)  # a Name of name, or a refusal
            return leaf, math.pi if name == "pi" else None, 0
        if op == "(":
            self.opened()
            inner = self.sum()
            self.closed()
            return inner
        raise _Unread

    def call(self, func: str) -> _Read:
        self.take()
        self.opened()
        built = [self.sum()]
        while self.tokens[self.at][2] == ",":
            self.take()
            self.term_ends()
            built.append(self.sum())
        self.closed()
        self.count += 1
        node, value = _applied(func, [(arg, value) for arg, value, _ in built])
        return node, value, 1 + max(height for _, _, height in built)


_Read = tuple[Node, Union[float, None], int]
_END = ("", "", "", "")
_PLAIN_NUMBER = re.compile(r"(?:0|[1-9]\d*)|(?:\d+\.\d*|\.\d+)(?:[eE][+-]?\d+)?|\d+[eE][+-]?\d+")
_FLOAT = re.compile(r"[.eE]")


class _Builder:
    """Checked trees from Python's syntax tree. Each part's constant value is carried up with
    it, so the bounds on constants (:func:`constant_value`) are checked once per part rather
    than refolded for every enclosing one."""

    _BINOPS: ClassVar = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/", ast.Pow: "**"}

    def __init__(self, functions: frozenset[str] | set[str], attributes: bool):
        self.functions = functions
        self.attributes = attributes
        self.count = 0

    def build(self, node: ast.AST, depth: int) -> Built:
        self.count += 1
        if self.count > MAX_NODES:
            raise ExpressionError(TOO_MANY_PARTS)
        if depth > MAX_DEPTH:
            raise ExpressionError(f"expected an expression nested at most {MAX_DEPTH} deep")
        if isinstance(node, ast.Constant):
            number = self._number(node.value)
            return number, number.value
        if isinstance(node, ast.Name):
            leaf = self._name(node.id)
            return leaf, math.pi if leaf == _PI else None
        if isinstance(node, ast.Attribute):
            if not self.attributes or not isinstance(node.value, ast.Name):
                raise ExpressionError("expected a unit vector such as N.x, found an attribute")
            base = self._name(node.value.id)
            if not isinstance(base, Name) or node.attr not in ("x", "y", "z"):
                raise ExpressionError(f"expected a unit vector such as N.x, "
                                      f"found '{node.value.id}.{node.attr}'")
            return Attr(base.id, node.attr), None
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            operand, value = self.build(node.operand, depth + 1)
            if isinstance(node.op, ast.UAdd):
                return operand, value
            return Unary("-", operand), None if value is None else -value
        if isinstance(node, ast.BinOp) and type(node.op) in self._BINOPS:
            return self._binary(node, self._BINOPS[type(node.op)], depth)
        if isinstance(node, ast.Call):
            return self._call(node, depth)
        raise ExpressionError(f"expected names, numbers, operators and functions, "
                              f"found {_describe(node)}")

    def _binary(self, node: ast.BinOp, op: str, depth: int) -> Built:
        # A flat chain a + b + c ... nests to the left; count it as one level, not many.
        chained = isinstance(node.left, ast.BinOp) and op != "**"
        left = self.build(node.left, depth + (0 if chained else 1))
        return _combined(op, left, self.build(node.right, depth + 1))

    def _call(self, node: ast.Call, depth: int) -> Built:
        if not isinstance(node.func, ast.Name):
            raise ExpressionError("expected a call of a named function such as sin(x)")
        func = node.func.id
        if func not in self.functions:
            raise ExpressionError(f"expected a known function ({_listing(self.functions)}), "
                                  f"found '{func}(...)'")
        if node.keywords or any(isinstance(a, ast.Starred) for a in node.args):
            raise ExpressionError(f"expected plain arguments in '{func}(...)'")
        return _applied(func, [self.build(a, depth + 1) for a in node.args])

    def _number(self, value) -> Num:
        if type(value) is int:  # most literals: a whole number's digits are its text
            text = str(value)
            if len(text) <= MAX_LITERAL_DIGITS:  # so below 1e30, within MAX_MAGNITUDE
                return Num(text)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ExpressionError(f"expected a number, found {_describe_constant(value)}")
        text = repr(value) if isinstance(value, float) else str(value)
        if len(text.replace("-", "").replace(".", "").split("e")[0]) > MAX_LITERAL_DIGITS:
            raise ExpressionError(f"expected a number of at most {MAX_LITERAL_DIGITS} digits")
        if not abs(value) <= MAX_MAGNITUDE:
            raise ExpressionError(f"expected numbers of at most {MAX_MAGNITUDE:g}, found "
                                  f"{excerpt(text)} {CONSTANT_PROBLEMS[0]}")
        return Num(text)

    def _name(self, name: str) -> Node:
        if name.startswith("_"):  # a rate's reading (__d1__x), or refused
            match = _RATE_NAME.fullmatch(name)
            if match:
                return Prime(match.group(2), int(match.group(1)))
            raise ExpressionError(f"expected names, numbers, operators and functions, "
                                  f"found '{name}' (names may not start with '_')")
        if name in self.functions:
            raise ExpressionError(f"expected '{name}(...)' with its argument in parentheses")
        return Name(name)


_PI = Name("pi")


def _combined(op: str, left: Built, right: Built) -> Built:
    """``left op right`` and its constant value, within the bounds on powers and constants."""
    (a_node, a), (b_node, b) = left, right
    out = Bin(op, a_node, b_node)
    if op == "**" and b is not None and abs(b) > MAX_POWER:
        raise ExpressionError(f"expected powers of at most {MAX_POWER}, found "
                              f"{excerpt(to_text(b_node))} {CONSTANT_PROBLEMS[0]}")
    if a is None or b is None:
        return out, None
    if op == "**":
        return out, _settled(out, _const_power, a, b)
    return out, _settled(out, PYTHON_OPERATORS[op], a, b)


def _applied(func: str, built: list[Built]) -> Built:
    """A call of ``func`` (a math function under its canonical name, with its number of
    arguments) and its constant value."""
    args = tuple(arg for arg, _ in built)
    if func in MATH_FUNCTIONS:
        canonical, arity = MATH_FUNCTIONS[func]
        if len(args) != arity:
            raise ExpressionError(f"expected {arity} argument{'s' * (arity > 1)} "
                                  f"for {func}(...), found {len(args)}")
        func = canonical
    call = Call(func, args)
    if func not in functions.CONSTANT_FUNCTIONS or len(args) != 1 or built[0][1] is None:
        return call, None
    return call, _settled(call, functions.CONSTANT_FUNCTIONS[func], built[0][1])


def _listing(functions: frozenset[str] | set[str]) -> str:
    shown = sorted(functions)
    return ", ".join(shown[:12]) + (", ..." if len(shown) > 12 else "")


def _describe(node: ast.AST) -> str:
    """The refused part as the writer would recognise it: rates shown with their primes
    again (``theta''``, not the reader's internal name), an equation named as such.

    >>> parse("θ̈ == -g")
    Traceback (most recent call last):
    ...
    mechgrade.errors.ExpressionError: expected names, numbers, operators and functions, found an equation "theta'' == -g" (write only its right-hand side)
    """
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
        return f"'{node.func.id}(...)'"
    try:
        text = ast.unparse(node)
    except Exception:  # pragma: no cover - unparse handles every parsed node
        text = type(node).__name__
    text = re.sub(r"__d([12])__([A-Za-z][A-Za-z0-9_]*)",
                  lambda m: m.group(2) + "'" * int(m.group(1)), text)
    if isinstance(node, ast.Compare):
        return f"an equation {text[:40]!r} (write only its right-hand side)"
    return repr(text[:40])


def _describe_constant(value) -> str:
    if isinstance(value, str):
        return "a string"
    if isinstance(value, complex):
        return "a complex number"
    return repr(value)[:20]


def constant_value(node: Node) -> float | None:
    """The value of a tree made only of numbers, operators, ``pi`` and math functions.

    Returns ``None`` when the tree uses a name; raises :class:`ExpressionError` ending with
    one of :data:`CONSTANT_PROBLEMS` when a constant is too large, divides by zero or is not a
    real number.

    >>> constant_value(parse("2**10 / 4"))
    256.0
    >>> constant_value(parse("x + 1")) is None
    True
    >>> constant_value(Call("exp", (Call("exp", (Num("1000"),)),)))
    Traceback (most recent call last):
    ...
    mechgrade.errors.ExpressionError: expected numbers of at most 1e+150, found 'exp(exp(1000))' (too large)
    """
    try:
        return _settled(node, _const, node)
    except _NotConstant:
        return None


TRIG_FUNCTIONS = frozenset({"sin", "cos", "tan", "cot", "sec", "csc"})


def degree_reading(node: Node) -> tuple[float, Call] | None:
    """A constant's value with the arguments of its trig functions read in degrees, and the
    first such call; ``None`` when no trig function takes a plain number (an argument with
    ``pi`` in it, or written with ``°``, is already an angle) or when that reading is no
    real number.

    >>> value, call = degree_reading(parse("2*sin(30)"))
    >>> round(value, 12), to_text(call)
    (1.0, 'sin(30)')
    >>> degree_reading(parse("sin(pi/6)")) is None, degree_reading(parse("sin(30°)")) is None
    (True, True)
    """
    first: list[Call] = []

    def call(func: str, args: tuple) -> float:
        value = _const(args[0]) if len(args) == 1 else None
        if func in TRIG_FUNCTIONS and value is not None and "pi" not in names(args[0]):
            if not first:
                first.append(Call(func, args))
            value *= math.pi / 180
        return _const_call(func, (Num(repr(value)),) if value is not None else args)

    try:
        value = _settled(node, lambda: fold(node, number=lambda n: n.value,
                                            resolve=_const_name, call=call,
                                            power=_const_power))
    except (ExpressionError, _NotConstant):
        return None
    return (value, first[0]) if first else None


def _settled(node: Node, operation, *operands) -> float:
    """``operation(*operands)``, the value of the constant part ``node``, within the bounds of
    :func:`constant_value` (which raises as it says)."""
    try:
        value = operation(*operands)
    except OverflowError:
        value = math.inf
    except ZeroDivisionError:
        raise ExpressionError(f"expected a defined constant, found {excerpt(to_text(node))} "
                              f"{CONSTANT_PROBLEMS[1]}") from None
    except ValueError:
        raise ExpressionError(f"expected a real constant, found {excerpt(to_text(node))} "
                              f"{CONSTANT_PROBLEMS[2]}") from None
    if not abs(value) <= MAX_MAGNITUDE:
        raise ExpressionError(f"expected numbers of at most {MAX_MAGNITUDE:g}, found "
                              f"{excerpt(to_text(node))} {CONSTANT_PROBLEMS[0]}")
    return value


AMBIGUOUS = "expected brackets"
"""How a refusal of text that reads two ways begins (``3g/2L``, ``√2gh``)."""

CONSTANT_PROBLEMS = ("(too large)", "(divides by zero)", "(not a real number)")
"""How a constant part can fail; readers refuse such text instead of trying other readings."""


class _NotConstant(Exception):
    pass


def _const_power(a: float, b: float) -> float:
    if abs(b) > MAX_POWER:
        raise OverflowError
    value = a ** b
    if isinstance(value, complex):
        raise ValueError
    return value


def _const_name(node: Node) -> float:
    if isinstance(node, Name) and node.id == "pi":
        return math.pi
    raise _NotConstant


def _const_call(func: str, args: tuple) -> float:
    if func not in functions.CONSTANT_FUNCTIONS or len(args) != 1:
        raise _NotConstant
    return functions.CONSTANT_FUNCTIONS[func](_const(args[0]))


def _const(node: Node) -> float:
    return fold(node, number=lambda n: n.value, resolve=_const_name, call=_const_call,
                power=_const_power)


PYTHON_OPERATORS = {"+": operator.add, "-": operator.sub, "*": operator.mul,
                    "/": operator.truediv, "**": operator.pow}


def fold(node: Node, *, number, resolve, call, power=operator.pow, divide=operator.truediv):
    """Evaluate a tree with Python's arithmetic, the leaves and calls given by the caller.

    ``number(Num)`` and ``resolve(Name | Prime | Attr)`` give leaf values; ``call(func, args)``
    receives the function name and the argument *trees* (so the caller chooses how to read
    them); ``power`` and ``divide`` may be replaced (numpy semantics, bounds). One walk serves
    sympy construction, constant folding and numeric sampling.

    >>> fold(parse("2*x + 1"), number=lambda n: n.value, resolve=lambda n: 3.0, call=None)
    7.0
    """
    def walk_(n: Node):
        if isinstance(n, Num):
            return number(n)
        if isinstance(n, (Name, Prime, Attr)):
            return resolve(n)
        if isinstance(n, Unary):
            return -walk_(n.operand)
        if isinstance(n, Bin):
            a, b = walk_(n.left), walk_(n.right)
            if n.op == "**":
                return power(a, b)
            if n.op == "/":
                return divide(a, b)
            return PYTHON_OPERATORS[n.op](a, b)
        return call(n.func, n.args)

    return walk_(node)


def additive_terms(node: Node, sign: int = 1) -> list[tuple[int, Node]]:
    """The additive terms of ``node`` with their signs.

    >>> [(s, to_text(t)) for s, t in additive_terms(parse("a + 2*b - c"))]
    [(1, 'a'), (1, '2*b'), (-1, 'c')]
    """
    if isinstance(node, Bin) and node.op in "+-":
        return additive_terms(node.left, sign) + additive_terms(node.right,
                                                     sign if node.op == "+" else -sign)
    if isinstance(node, Unary) and node.op == "-":
        return additive_terms(node.operand, -sign)
    return [(sign, node)]


def sum_of_terms(terms: list[tuple[int, Node]]) -> Node:
    """The sum of signed terms (:func:`additive_terms`' inverse)."""
    sign, node = terms[0]
    total = node if sign > 0 else Unary("-", node)
    for sign, node in terms[1:]:
        total = Bin("+" if sign > 0 else "-", total, node)
    return total
