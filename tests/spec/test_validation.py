"""Every way a problem file can be wrong gives one located message (file:line:col: field: ...)."""

from __future__ import annotations

from pathlib import Path

import pytest

import math

from mechgrade.errors import SpecError, SpecErrors
from mechgrade.spec import load_problem, load_problem_text

DATA = Path(__file__).resolve().parents[1] / "data"

BASE = (DATA / "spec" / "base.yaml").read_text()


def error_of(text: str) -> str:
    with pytest.raises(SpecError) as info:
        load_problem_text(text, "p.yaml")
    return str(info.value)


def mutated(old: str, new: str) -> str:
    assert old in BASE, old
    return BASE.replace(old, new, 1)


def test_base_problem_loads():
    problem = load_problem_text(BASE, "p.yaml")
    assert problem.id == "base"
    assert [g.key.text for g in problem.givens] == ["theta", "L", "theta'", "theta''"]


CASES = [
    # YAML
    ("empty file", "", "p.yaml: expected a mapping of problem fields (id, title, ...), found an empty file"),
    ("yaml syntax", BASE + "  bad: [1,\n", "p.yaml:25:3: indentation: this line is indented 2 spaces, the key above 4"),
    ("alias", BASE.replace("L: m", "L: &u m\n  M: *u"), "p.yaml:13:6: expected plain YAML, found an alias (*name); anchors and aliases are not allowed"),
    ("duplicate key", BASE.replace("L: m", "L: m\n  L: ft"), "p.yaml:13:3: parameters.L: expected each key once, found 'L' again"),
    # schema
    ("unknown key", BASE + "colour: red\n", "p.yaml:25:1: colour: expected only the fields id, title, source, statement, tags, inertial, frames, points, coordinates, parameters, constraints, givens, guesses, unknown, branch, define, variants, consistency, bodies, loads, analysis, objectives, found 'colour'"),
    ("missing key", BASE.replace("title: Base problem for validation tests\n", ""), "p.yaml:1:1: expected a field 'title', found none"),
    ("wrong type", mutated("title: Base problem for validation tests", "title: [a]"), "p.yaml:2:8: title: expected text, found a list of 1"),
    ("bad kind", mutated("kind: scalar", "kind: number"), "p.yaml:22:11: objectives[0].kind: expected one of scalar, vector, symbolic, found 'number'"),
    ("bad name", mutated("  P: {from: O", "  2P: {from: O"), "p.yaml:8:3: points.2P: expected a name made of letters, digits and '_', starting with a letter, found '2P'"),
    ("no objectives", BASE.split("objectives:")[0] + "objectives: []\n", "p.yaml:18:13: objectives: expected at least 1 item(s), found an empty list"),
    ("rotation and rotations", mutated("rotation: {axis: z, angle: theta}", "rotation: {axis: z, angle: theta}, rotations: [{axis: x, angle: 0}]"), "p.yaml:6:6: frames.A: expected only one of the fields rotation, rotations, found rotation and rotations"),
    ("bad axis", mutated("axis: z", "axis: w"), "p.yaml:6:35: frames.A.rotation.axis: expected one of x, y, z, found 'w'"),
    ("equation without =", BASE.replace("givens:", "constraints:\n  - {name: c, position: theta}\ngivens:"), "p.yaml:14:25: constraints[0].position: expected an equation 'left = right', found 'theta'"),
    ("book without note", mutated("expect: {value: 6}", "expect: {value: 6, book: 7}"), "p.yaml:24:13: objectives[0].expect: expected a field 'note' (why the book's printed answer differs) with 'book', found none"),
    ("tolerance too big", mutated("    expect: {value: 6}", "    tolerance: {rel: 2}\n    expect: {value: 6}"), "p.yaml:24:22: objectives[0].tolerance.rel: expected a number <= 1, found 2"),
    # expressions and units
    ("unreadable expression", mutated("position: L*A.x", "position: L*A.x +"), "p.yaml:8:26: points.P.position: expected a complete expression, found 'L*A.x +' (invalid syntax)"),
    ("eval payload", mutated("position: L*A.x", "position: __import__(1)"), "points.P.position: expected names, numbers, operators and functions, found '__import__'"),
    ("bad unit", mutated("L: m", "L: furlongz"), "p.yaml:12:6: parameters.L: expected a unit such as 'm/s^2', found 'furlongz' ('furlongz' is not a unit)"),
    ("bad quantity", mutated("L: 2 m", "L: two m"), "p.yaml:15:6: givens.L: expected a number followed by a unit such as '9.81 m/s^2', found 'two m'"),
    ("given value not constant", mutated("L: 2 m", "L: {value: x/2, unit: m}"), "p.yaml:15:6: givens.L: expected a number or a constant expression such as pi/2, found 'x/2'"),
    # names
    ("reserved name", mutated("L: m", "t: m"), "p.yaml:12:3: parameters.t: 't' is reserved (time, pi or a function name); expected another parameter name"),
    ("coordinate and parameter", mutated("L: m", "L: m\n  theta: rad"), "p.yaml:10:3: coordinates.theta: 'theta' is both a coordinate and a parameter; expected distinct names"),
    ("frame named like a coordinate", mutated("  A: {parent: N", "  theta: {parent: N"), "p.yaml:6:3: frames.theta: 'theta' names a frame or point and also a coordinate or parameter"),
    ("rate name clash", mutated("L: m", "L: m\n  thetad: rad/s"), "p.yaml:13:3: parameters.thetad: parameter 'thetad' clashes with the rate name of coordinate 'theta'"),
    ("inertial point listed", mutated("  P: {from: O, position: L*A.x}", "  P: {from: O, position: L*A.x}\n  O: {from: P, position: L*A.x}"), "p.yaml:9:3: points.O: 'O' is the inertial point; expected it under 'inertial' only, not also under points"),
    ("unknown parent", mutated("parent: N", "parent: Q"), "p.yaml:6:15: frames.A.parent: unknown parent frame 'Q' (expected one of: N, A)"),
    ("unknown origin", mutated("origin: O", "origin: Z"), "p.yaml:6:61: frames.A.origin: unknown origin point 'Z' (expected one of: O, P)"),
    ("frame cycle", mutated("  A: {parent: N, rotation: {axis: z, angle: theta}, origin: O}", "  A: {parent: B, rotation: {axis: z, angle: theta}, origin: O}\n  B: {parent: A, rotation: {axis: z, angle: 0}}"), "frames.A: frame 'A' is oriented through a cycle of parents (A -> B -> A); expected a tree rooted at 'N'"),
    ("angle with units", mutated("angle: theta}", "angle: L}"), "p.yaml:6:45: frames.A.rotation.angle: dimension mismatch in 'L': expected a pure number (or an angle), found a length ([length])"),
    ("unknown from point", mutated("{from: O, position", "{from: Q, position"), "p.yaml:8:13: points.P.from: unknown point 'Q' in 'from' (expected one of: O, P)"),
    ("position not a vector", mutated("position: L*A.x", "position: L"), "p.yaml:8:26: points.P.position: expected a position vector (a length times unit vectors, e.g. L*A.x), found a scalar ('L')"),
    ("position not a length", mutated("position: L*A.x", "position: theta*A.x"), "points.P.position: dimension mismatch in 'theta*A.x': expected a length ([length]), found a pure number (or an angle)"),
    ("point cycle", mutated("  P: {from: O, position: L*A.x}", "  P: {from: Q, position: L*A.x}\n  Q: {from: P, position: L*A.x}"), "points.P: point 'P' is located through a cycle (P -> Q -> P); expected a chain ending at 'O'"),
    # constraints
    ("duplicate constraint", BASE.replace("givens:", "constraints:\n  - {name: c, position: theta = 0}\n  - {name: c, position: L = 1}\ngivens:"), "constraints[1]: constraint name 'c' used twice"),
    ("equation kinds", BASE.replace("givens:", "constraints:\n  - {name: c, position: L*A.x = L}\ngivens:"), "constraints[0].position: expected both sides of the equation to be of the same kind, found a vector and a scalar"),
    ("equation dimensions", BASE.replace("givens:", "constraints:\n  - {name: c, position: L = theta}\ngivens:"), "constraints[0].position: dimension mismatch in both sides of the equation: expected a pure number (or an angle), found a length ([length])"),
    # givens
    ("given vector", mutated("  L: 2 m", "  L: 2 m\n  A.x: 1"), "givens.A.x: expected a scalar quantity as a given's name, found a vector ('A.x')"),
    ("a value with its unit", mutated("position: L*A.x", "position: 2 m*A.x"), "p.yaml:8:26: points.P.position: expected names in an expression, found '2 m', a value with its unit: declare a parameter (say T: m), give its value under givens (T: 2 m) and write T here"),
    ("given unknown", mutated("  L: 2 m", "  L: 2 m\n  M: 1 kg"), "givens.M: unknown name 'M' (expected a coordinate, parameter, t or pi; known: L, theta)"),
    ("given third derivative", mutated("  L: 2 m", "  L: 2 m\n  theta''': 1 rad/s^3"), "p.yaml:16:13: givens.theta''': expected a prime (') only right after a name, as in theta'"),
    ("given twice", mutated("  L: 2 m", "  L: 2 m\n  L : 3 m"), "expected each key once"),
    ("given canonical twice", mutated("  L: 2 m", "  L: 2 m\n  (L): 3 m"), "givens.(L): 'L' is given twice"),
    ("given dimension", mutated("  L: 2 m", "  L: 2 s"), "p.yaml:15:6: givens.L: dimension mismatch in the value of 'L': expected a length ([length]), found a time ([time])"),
    ("guess not coordinate", mutated("givens:", "guesses:\n  theta': 1 rad/s\ngivens:"), "guesses.theta': expected a coordinate or parameter to guess, found 'theta''"),
    ("guess dimension", mutated("givens:", "guesses:\n  theta: 1 m\ngivens:"), "guesses.theta: dimension mismatch in the guess for 'theta'"),
    # objectives
    ("duplicate objective", BASE + "  - {id: speed, prompt: p, find: 'speed(P, N)', kind: scalar, unit: m/s}\n", "objectives[1]: objective id 'speed' used twice"),
    ("kind mismatch", mutated("find: speed(P, N)", "find: vel(P, N)"), "p.yaml:21:11: objectives[0].find: expected a scalar expression for a scalar objective, found a vector ('vel(P, N)')"),
    ("unit mismatch", mutated("unit: m/s", "unit: m/s^2"), "p.yaml:21:11: objectives[0].find: dimension mismatch in objective 'speed' (unit 'm/s^2'): expected an acceleration ([length]/[time]²), found a velocity ([length]/[time])"),
    ("vector without frame", mutated("find: speed(P, N)\n    kind: scalar", "find: vel(P, N)\n    kind: vector"), "objectives[0]: a vector objective needs 'frame'"),
    ("unknown objective frame", mutated("kind: scalar", "kind: scalar\n    frame: Q"), "p.yaml:23:12: objectives[0].frame: unknown frame 'Q' (expected one of: N, A)"),
    ("symbolic without symbols", mutated("kind: scalar", "kind: symbolic"), "objectives[0]: a symbolic objective needs 'symbols'"),
    ("symbols on scalar", mutated("kind: scalar", "kind: scalar\n    symbols: [L]"), "objectives[0]: 'symbols' belongs to symbolic objectives only"),
    ("unknown symbol", mutated("kind: scalar", "kind: symbolic\n    symbols: [omega]").replace("expect: {value: 6}", "expect: {expr: omega}"), "objectives[0].symbols[0]: symbol 'omega' is not a parameter, coordinate or rate name (such as thetad)"),
    ("bad symbol alias", mutated("kind: scalar", "kind: symbolic\n    symbols: [{omega: 'L*2'}]").replace("expect: {value: 6}", "expect: {expr: omega}"), "objectives[0].symbols[0]: expected symbol 'omega' to stand for a parameter, coordinate or rate, found 'L*2'"),
    ("expect shape", mutated("expect: {value: 6}", "expect: {components: [6, 0]}"), "objectives[0].expect: expected 'expect.value' for a scalar objective, found 'expect.components'"),
    ("expect unit", mutated("expect: {value: 6}", "expect: {value: 6, unit: s}"), "objectives[0].expect: dimension mismatch in expect.unit of 'speed'"),
    ("expect expr symbol", mutated("kind: scalar", "kind: symbolic\n    symbols: [L, thetad]").replace("expect: {value: 6}", "expect: {expr: L*thetad*g}"), "objectives[0].expect: expect.expr uses 'g', which is not among the objective's symbols (L, thetad)"),
    ("mistake kind", mutated("expect: {value: 6}", "mistakes: [{find: 'vel(P, N)', message: m}]\n    expect: {value: 6}"), "objectives[0].mistakes[0].find: expected the mistaken model of 'speed' to be of the same kind, found a scalar and a vector"),
    ("depends_on unknown", mutated("expect: {value: 6}", "depends_on: [nope]\n    expect: {value: 6}"), "p.yaml:24:18: objectives[0].depends_on[0]: depends_on names unknown objective 'nope' (expected one of: none)"),
    # typing inside expressions
    ("point as scalar", mutated("find: speed(P, N)", "find: P"), "objectives[0].find: 'P' is a point; expected a scalar or vector here"),
    ("prime of parameter", mutated("find: speed(P, N)", "find: L'"), "objectives[0].find: expected a coordinate before the prime, found 'L'"),
    ("unknown unit-vector frame", mutated("position: L*A.x", "position: L*Q.x"), "points.P.position: unknown frame 'Q' in 'Q.x' (frames: N, A)"),
    ("scalar plus vector", mutated("position: L*A.x", "position: L*A.x + L"), "points.P.position: cannot add a vector and a scalar in 'L*A.x+L'"),
    ("length plus angle", mutated("find: speed(P, N)", "find: L + theta"), "objectives[0].find: cannot add a length ([length]) and a pure number (or an angle) in 'L+theta'"),
    ("vector times vector", mutated("position: L*A.x", "position: L*A.x*A.y"), "cannot multiply two vectors in 'L*A.x*A.y'; expected dot(u, v) or cross(u, v)"),
    ("divide by vector", mutated("position: L*A.x", "position: L/A.x"), "expected a nonzero scalar divisor in 'L/A.x'"),
    ("vector power", mutated("position: L*A.x", "position: A.x**2"), "cannot raise a vector to a power in 'A.x**2'"),
    ("exponent with units", mutated("find: speed(P, N)", "find: theta**L"), "expected a pure-number exponent in 'theta**L'"),
    ("variable exponent of dimensional", mutated("find: speed(P, N)", "find: L**theta"), "a quantity with units needs a constant exponent in 'L**theta'"),
    ("wrong arity", mutated("find: speed(P, N)", "find: speed(P)"), "expected 2 arguments for speed(...) (speed(P, F): speed (s-dot) of P in F), found 1"),
    ("ic outside pos", mutated("find: speed(P, N)", "find: speed(ic(A, N), N)"), "ic(A, F) is a point: use it as pos(ic(A, F), P)"),
    ("frame argument", mutated("find: speed(P, N)", "find: speed(P, P)"), "expected a frame as argument of speed(...), found 'P' (frames: N, A)"),
    ("point argument", mutated("find: speed(P, N)", "find: speed(N.x, N)"), "expected a point as argument of speed(...), found 'N.x'"),
    ("vector argument", mutated("find: speed(P, N)", "find: mag(L)"), "expected a vector as argument of mag(...), found a scalar ('L')"),
    ("needs origin", mutated(", origin: O}", "}"), "speed(...) needs a point fixed in frame") if False else ("needs origin", mutated(", origin: O}", "}").replace("find: speed(P, N)", "find: speed(P, A)"), "objectives[0].find: speed(...) needs a point fixed in frame 'A': give the frame an 'origin'"),
    ("math of vector", mutated("find: speed(P, N)", "find: sin(vel(P, N))"), "sin(...) takes a scalar, found a vector (use mag(v) or dot(u, v))"),
    ("atan2 dimensions", mutated("find: speed(P, N)", "find: atan2(L, theta)"), "atan2(y, x) needs y and x in the same dimension"),
    ("sin of length", mutated("find: speed(P, N)", "find: sin(L)"), "sin(...) needs a pure number or angle, found a length ([length])"),
]


@pytest.mark.parametrize("text, message", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_problem_gives_located_message(text, message):
    err = error_of(text)
    assert message in err
    assert err.startswith("p.yaml")


def test_missing_file_is_reported(tmp_path):
    with pytest.raises(SpecError, match=r"expected a problem file \(YAML\), found no such file"):
        load_problem(tmp_path / "absent.yaml")


def test_binary_file_is_reported(tmp_path):
    path = tmp_path / "x.yaml"
    path.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00")
    with pytest.raises(SpecError, match="expected UTF-8 text, found byte 0x89"):
        load_problem(path)


# ---------------------------------------------------------------- every error at once


def errors_of(text: str, name: str = "base.yaml") -> list[str]:
    with pytest.raises(SpecError) as info:
        load_problem_text(text, name)
    return str(info.value).splitlines()


def test_independent_errors_come_together_in_file_order():
    text = (BASE.replace("kind: scalar", "kind: scalr").replace("L: 2 m", "L: 2 s")
            .replace("parent: N", "parent: NN"))
    with pytest.raises(SpecErrors) as info:
        load_problem_text(text, "base.yaml")
    assert [e.where.line for e in info.value.errors] == [6, 15, 22]
    assert str(info.value).splitlines() == [
        "base.yaml:6:15: frames.A.parent: unknown parent frame 'NN'; did you mean 'N'? "
        "(expected one of: N, A)",
        "base.yaml:15:6: givens.L: dimension mismatch in the value of 'L': expected a length "
        "([length]), found a time ([time])",
        "base.yaml:22:11: objectives[0].kind: expected one of scalar, vector, symbolic, "
        "found 'scalr'; did you mean 'scalar'?",
    ]


@pytest.mark.parametrize("old, new, message", [
    ("angle: theta}", "angle: theta +}",
     "base.yaml:6:45: frames.A.rotation.angle: expected a complete expression, found 'theta +' "
     "(invalid syntax)"),
    ("L: m", "L: furlongz",
     "base.yaml:12:6: parameters.L: expected a unit such as 'm/s^2', found 'furlongz' "
     "('furlongz' is not a unit)"),
    ("theta: rad", "theta: radz",
     "base.yaml:10:10: coordinates.theta: expected a unit such as 'm/s^2', found 'radz' "
     "('radz' is not a unit); did you mean 'rad'?"),
    ("  P: {from: O, position: L*A.x}", "  - P", "base.yaml:8:3: points: expected a mapping, "
     "found a list of 1"),
    ("  A: {parent: N,", "  A: {parnt: N,", "base.yaml:6:7: frames.A.parnt: expected only the fields parent, rotation, "
     "rotations, origin, found 'parnt'; did you mean 'parent'?"),
    ("title:", "titel:", "base.yaml:2:1: titel: expected only the fields id, title, source, statement, tags, "
     "inertial, frames, points, coordinates, parameters, constraints, givens, guesses, unknown, "
     "branch, define, variants, consistency, bodies, loads, analysis, objectives, found 'titel'; "
     "did you mean 'title'?"),
    ("find: speed(P, N)", "find: speed(P,, N)", "base.yaml:21:11: objectives[0].find: expected "
     "a complete expression, found 'speed(P,, N)' (invalid syntax)"),
])
def test_a_failed_definition_is_reported_once_without_cascade(old, new, message):
    assert errors_of(mutated(old, new)) == [message]


@pytest.mark.parametrize("old, new, message", [
    ("find: speed(P, N)", "find: speeed(P, N)",
     "objectives[0].find: unknown function 'speeed(...)'; did you mean 'speed'?"),
    ("find: speed(P, N)", "find: speed(Pt, N)",
     "objectives[0].find: expected a point as argument of speed(...), found 'Pt'; did you mean "
     "'P'? (points: O, P)"),
    ("find: speed(P, N)", "find: speed(P, NN)",
     "objectives[0].find: expected a frame as argument of speed(...), found 'NN'; did you mean "
     "'N'? (frames: N, A)"),
    ("position: L*A.x", "position: L*AA.x",
     "points.P.position: unknown frame 'AA' in 'AA.x'; did you mean 'A'? (frames: N, A)"),
    ("find: speed(P, N)", "find: thetaa'",
     "objectives[0].find: expected a coordinate before the prime, found 'thetaa'; did you mean "
     "'theta'? (coordinates: theta)"),
    ("  L: 2 m", "  Lx: 2 m", "givens.Lx: unknown name 'Lx'; did you mean 'L'?"),
    ("theta'': 1 rad/s^2", "thetadd: 1 rad/s^2",
     "givens.thetadd: unknown name 'thetadd'; did you mean \"theta''\"?"),
    ("{from: O, position", "{from: OO, position",
     "base.yaml:8:13: points.P.from: unknown point 'OO' in 'from'; did you mean 'O'?"),
])
def test_close_names_are_suggested(old, new, message):
    assert message in "\n".join(errors_of(mutated(old, new)))


@pytest.mark.parametrize("old, new, message", [
    ("theta: 30 deg", "theta: 30", "base.yaml:14:10: givens.theta: expected an angle with its "
     "unit, found the bare number 30; write `30 deg` or `0.524 rad`"),
    ("theta: 30 deg", "theta: {value: 40}", "base.yaml:14:10: givens.theta: expected an angle "
     "with its unit, found the bare number 40; write `40 deg` or `0.698 rad`"),
    ("givens:", "guesses:\n  theta: 1\ngivens:", "base.yaml:14:10: guesses.theta: expected an "
     "angle with its unit, found the bare number 1; write `1 deg` or `0.0175 rad`"),
    ("angle: theta}", "angle: -25}", "base.yaml:6:45: frames.A.rotation.angle: expected an angle "
     "with its unit, found the bare number -25; write `-25 deg` or `-0.436 rad`"),
    ("angle: theta}", "angle: 25 m}", "base.yaml:6:45: frames.A.rotation.angle: expected an "
     "angle such as '25 deg', found '25 m'"),
    ("theta': 3 rad/s", "theta': 3", "base.yaml:16:11: givens.theta': expected a value with its "
     "unit (an angular velocity or rate (1/[time])), found the bare number 3; write `3 rad/s`"),
    ("L: 2 m", "L: 2", "base.yaml:15:6: givens.L: expected a value with its unit (a length "
     "([length])), found the bare number 2; write `2 m`"),
])
def test_bare_numbers_need_a_unit(old, new, message):
    assert errors_of(mutated(old, new)) == [message]


@pytest.mark.parametrize("old, new", [
    ("theta: 30 deg", "theta: 0"),
    ("theta: 30 deg", "theta: {value: pi/6}"),
    ("theta: 30 deg", "theta: 0.5236 rad"),
    ("  L: 2 m", "  L: 2 m\n  n: 3"),  # a pure number (n is declared in '1')
])
def test_unambiguous_numbers_load(old, new):
    load_problem_text(mutated(old, new).replace("  L: m\n", "  L: m\n  n: 1\n"), "base.yaml")


def test_a_rotation_angle_may_carry_its_unit():
    problem = load_problem_text(mutated("angle: theta}", "angle: 90 deg}"), "base.yaml")
    angle = problem.frames[1].rotations[0].angle
    assert angle.text == "90 deg" and angle.node.value == pytest.approx(math.pi / 2)


def test_id_differing_from_file_name_is_a_warning():
    assert load_problem_text(BASE, "base.yaml").warnings == ()
    assert load_problem_text(BASE, "<problem>").warnings == ()
    (warning,) = load_problem_text(BASE, "dir/copy.yml").warnings
    assert str(warning) == ("dir/copy.yml:1:5: id: warning: id 'base' differs from the file name "
                            "'copy'; expected them equal (rename the file or write id: copy)")


def test_names_defined_twice_point_at_the_key():
    assert errors_of(mutated("L: m", "L: m\n  theta: rad")) == [
        "base.yaml:10:3: coordinates.theta: 'theta' is both a coordinate and a parameter; "
        "expected distinct names"]


def test_a_badly_formed_name_spoils_its_section_without_cascade():
    assert errors_of(mutated("  P: {from: O", "  2P: {from: O")) == [
        "base.yaml:8:3: points.2P: expected a name made of letters, digits and '_', starting "
        "with a letter, found '2P'"]


def test_the_sign_of_a_quantity_is_a_pure_number_as_in_student_answers():
    problem = load_problem_text(mutated("find: speed(P, N)", "find: speed(P, N)*sign(L)"),
                                "p.yaml")
    assert problem.objectives[0].find.text == "speed(P, N)*sign(L)"


def test_objective_kinds_are_typed_and_read_as_their_text():
    from mechgrade.spec.model import ObjectiveKind

    objective = load_problem_text(BASE, "p.yaml").objectives[0]
    assert objective.kind is ObjectiveKind.SCALAR
    assert objective.kind == "scalar" and f"{objective.kind}" == "scalar"


ROOT = Path(__file__).resolve().parents[2]
VARIANTS = (ROOT / "examples" / "hw2_variants" / "pendulum_variants.yaml").read_text()
LADDER = (ROOT / "problems" / "ladder_wall_lift_off.yaml").read_text()
FLYWHEEL = (ROOT / "problems" / "flywheel_speed_drop.yaml").read_text()
LIMACON = (ROOT / "problems" / "ruina_10_2_limacon.yaml").read_text()
TOLERANCE = "    tolerance: {rel: 0.01}\n    expect: {value: 6}"

# One failing input per kind of numeric field: NaN, infinity and magnitudes no physical value
# reaches are refused at load, located, before anything is solved or graded.
NUMBER_CASES = [
    ("tolerance rel nan", BASE, "    expect: {value: 6}", TOLERANCE.replace("0.01", ".nan"),
     "p.yaml:24:22: objectives[0].tolerance.rel: expected a finite number, found nan (not a "
     "number)"),
    ("tolerance abs inf", BASE, "    expect: {value: 6}",
     TOLERANCE.replace("rel: 0.01", "abs: .inf"),
     "p.yaml:24:22: objectives[0].tolerance.abs: expected a finite number, found inf "
     "(infinite)"),
    ("tolerance abs huge", BASE, "    expect: {value: 6}",
     TOLERANCE.replace("rel: 0.01", "abs: 1.0e+300"),
     "p.yaml:24:22: objectives[0].tolerance.abs: expected a number of magnitude at most "
     "1e+40, found 1e+300"),
    ("expect value nan", BASE, "expect: {value: 6}", "expect: {value: .nan}",
     "p.yaml:24:21: objectives[0].expect.value: expected a finite number, found nan (not a "
     "number)"),
    ("given as a YAML number", BASE, "theta'': 1 rad/s^2", "theta'': -.inf",
     "p.yaml:17:12: givens.theta'': expected a finite number, found -inf (infinite)"),
    ("given value in a mapping", BASE, "L: 2 m", "L: {value: .nan, unit: m}",
     "p.yaml:15:14: givens.L.value: expected a finite number, found nan (not a number)"),
    ("given with a unit", BASE, "L: 2 m", "L: 1.0e300 ft",
     "p.yaml:15:6: givens.L: expected a number of magnitude at most 1e+40 in SI units, found "
     "'1.0e300 ft'"),
    ("given too small", BASE, "L: 2 m", "L: 1e-300 m",
     "p.yaml:15:6: givens.L: expected zero or a number of magnitude at least 1e-40 in SI "
     "units, found '1e-300 m'"),
    ("given worked out from others", BASE, "theta': 3 rad/s\n  theta'': 1 rad/s^2",
     "theta': 1e30 rad/s\n  theta'': theta'^2",
     "p.yaml:17:12: givens.theta'': expected a number of magnitude at most 1e+40 in SI "
     "units, found \"theta'^2\""),
    ("number in an expression", BASE, "position: L*A.x", "position: 1e100*L*A.x",
     "p.yaml:8:26: points.P.position: expected a number of magnitude at most 1e+40, found "
     "1e+100"),
    ("mistake credit", BASE, "expect: {value: 6}",
     "expect: {value: 6}\n    mistakes: [{find: L, message: m, credit: .nan}]",
     "p.yaml:25:46: objectives[0].mistakes[0].credit: expected a finite number, found nan "
     "(not a number)"),
    ("consistency", BASE, "objectives:", "consistency: .nan\nobjectives:",
     "p.yaml:18:14: consistency: expected a finite number, found nan (not a number)"),
    ("guess", LIMACON, "R: 1 ft", "R: 1e99 ft",
     "p.yaml:34:6: guesses.R: expected a number of magnitude at most 1e+40 in SI units, found "
     "'1e99 ft'"),
    ("variant range", VARIANTS, "from: 1.5 ft", "from: .nan",
     "p.yaml:26:15: variants.draw.L.from: expected a finite number, found nan (not a number)"),
    ("variant range with a unit", VARIANTS, "to: 4 ft", "to: 4e99 ft",
     "variants.draw.L: expected a number of magnitude at most 1e+40, found 4e+99"),
    ("variant choice", VARIANTS, "[20 deg,", "[1e50,",
     "p.yaml:27:12: variants.draw.theta: expected a number of magnitude at most "
     "1e+40, found 1e+50"),
    ("integration time limit", LADDER, "max_time: 10 s", "max_time: .inf",
     "p.yaml:34:15: analysis.integrate.max_time: expected a finite number, found inf "
     "(infinite)"),
    ("integration time limit with a unit", LADDER, "max_time: 10 s", "max_time: 1e300 s",
     "analysis.integrate: expected a number of magnitude at most 1e+40, found 1e+300"),
    ("design guess", FLYWHEEL, "guess: 0.5 m", "guess: 1e-60 m",
     "analysis.design: expected zero or a number of magnitude at least 1e-40, found 1e-60"),
]


@pytest.mark.parametrize("base, old, new, message", [c[1:] for c in NUMBER_CASES],
                         ids=[c[0] for c in NUMBER_CASES])
def test_numbers_no_physical_value_reaches_are_refused_at_load(base, old, new, message):
    assert old in base, old
    assert message in error_of(base.replace(old, new, 1))
