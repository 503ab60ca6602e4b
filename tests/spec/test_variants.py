"""The variants: section: what it reads, and one located message for each way it can be wrong."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from mechgrade.errors import SpecError
from mechgrade.spec import load_problem_text
from mechgrade.spec.variants import Choices, Integers, RoundedRange, SteppedRange

BASE = (Path(__file__).resolve().parents[1] / "data" / "spec" / "base.yaml").read_text()
# base.yaml: givens theta (30 deg), L (2 m), theta' (3 rad/s), theta'' (1 rad/s^2); objective speed


def with_variants(section: str, statement: str | None = None) -> str:
    text = BASE.replace("objectives:", section.strip("\n") + "\nobjectives:", 1)
    if statement is not None:
        text = text.replace("statement: A pendulum of length L turns about O.",
                            f"statement: {statement}")
    return text


def error_of(text: str) -> str:
    with pytest.raises(SpecError) as info:
        load_problem_text(text, "p.yaml")
    return str(info.value)


GOOD = """
variants:
  draw:
    L: {from: 100 cm, to: 3, step: 0.5}
    theta: {choices: [20 deg, 0.5 rad]}
    theta': {from: 2 rad/s, to: 4 rad/s, sig_figs: 2}
    theta'': {integers: [1, 5]}
  require: ["theta' > L"]
  bounds:
    speed: {min: 1 m/s, max: 2000 cm/s}
    theta: {max: 90 deg}
"""


def test_each_kind_of_draw_is_read_in_the_given_unit():
    problem = load_problem_text(with_variants(GOOD, "Length {L}, angle {theta}."), "p.yaml")
    draws = {d.key: d for d in problem.variants.draws}
    assert draws["L"] == SteppedRange("L", "m", 1.0, 3.0, 0.5)
    assert isinstance(draws["theta"], Choices)
    assert draws["theta"].values[0] == 20.0
    assert round(draws["theta"].values[1], 4) == round(0.5 * 180 / 3.141592653589793, 4)
    assert draws["theta'"] == RoundedRange("theta'", "rad / s", 2.0, 4.0, 2)
    assert draws["theta''"] == Integers("theta''", "rad / s ** 2", 1, 5)
    bounds = {b.name: b for b in problem.variants.bounds}
    assert (bounds["speed"].low, bounds["speed"].high, bounds["speed"].unit) == (1.0, 20.0, "m/s")
    assert (bounds["theta"].low, bounds["theta"].unit) == (None, "rad")
    assert bounds["theta"].high == pytest.approx(math.pi / 2)  # in the coordinate's unit
    assert problem.variants.requires[0].holds({"theta'": 3.0, "L": 2.0, "theta": 0.5,
                                               "theta''": 1.0})


def test_a_problem_without_variants_has_none():
    assert load_problem_text(BASE, "p.yaml").variants is None


CASES = [
    ("unknown given", "variants:\n  draw:\n    Lx: {from: 1 m, to: 2 m, step: 0.1 m}\n",
     "p.yaml:20:9: variants.draw.Lx: expected a given of the problem to draw (theta, L, "
     "theta', theta''), found 'Lx'; did you mean 'L'?"),
    ("wrong dimension", "variants:\n  draw:\n    L: {from: 1 s, to: 2 m, step: 0.1 m}\n",
     "p.yaml:20:15: variants.draw.L.from: expected a value in units like m (the given's unit), "
     "found '1 s'"),
    ("unknown unit", "variants:\n  draw:\n    L: {from: 1 mq, to: 2 m, step: 0.1 m}\n",
     "p.yaml:20:15: variants.draw.L.from: expected a unit such as 'm/s^2', found ' mq' "
     "('mq' is not a unit)"),
    ("bool value", "variants:\n  draw:\n    L: {choices: [true]}\n",
     "p.yaml:20:19: variants.draw.L.choices[0]: expected text or a number, found true"),
    ("empty range", "variants:\n  draw:\n    L: {from: 2 m, to: 1 m, step: 0.1 m}\n",
     "p.yaml:20:8: variants.draw.L: expected 'from' below 'to', found 2 and 1 m"),
    ("to missing", "variants:\n  draw:\n    L: {from: 2 m, step: 0.1 m}\n",
     "p.yaml:20:8: variants.draw.L.to: expected 'to' with 'from' (a range needs both ends)"),
    ("step and sig_figs", "variants:\n  draw:\n    L: {from: 1 m, to: 2 m, step: 0.1 m, sig_figs: 2}\n",
     "p.yaml:20:8: variants.draw.L: expected exactly one of 'step' and 'sig_figs' with a range"),
    ("neither step nor sig_figs", "variants:\n  draw:\n    L: {from: 1 m, to: 2 m}\n",
     "p.yaml:20:8: variants.draw.L: expected exactly one of 'step' and 'sig_figs' with a range"),
    ("zero step", "variants:\n  draw:\n    L: {from: 1 m, to: 2 m, step: 0 m}\n",
     "p.yaml:20:35: variants.draw.L.step: expected a positive step, found '0 m'"),
    ("integers reversed", "variants:\n  draw:\n    theta'': {integers: [5, 1]}\n",
     "p.yaml:20:25: variants.draw.theta''.integers: expected integers [low, high] with "
     "low <= high, found [5, 1]"),
    ("two kinds", "variants:\n  draw:\n    L: {choices: [1 m], integers: [1, 2]}\n",
     "p.yaml:20:8: variants.draw.L: expected only one of from, choices, integers, found "
     "choices, integers"),
    ("no kind", "variants:\n  draw:\n    L: {step: 1 m}\n",
     "p.yaml:20:8: variants.draw.L: expected one of the keys from (with to), choices, "
     "integers"),
    ("misspelt kind", "variants:\n  draw:\n    L: {choice: [1 m]}\n",
     "p.yaml:20:9: variants.draw.L.choice: expected only the fields from, to, step, "
     "sig_figs, choices, integers, found 'choice'; did you mean 'choices'?"),
    ("draw missing", "variants:\n  require: [L > 1]\n",
     "p.yaml:19:3: variants: expected a field 'draw', found none"),
    ("not a condition", "variants:\n  draw:\n    L: {choices: [1 m]}\n  require: [L = 1]\n",
     "p.yaml:21:13: variants.require[0]: expected a condition 'left < right' (one of <, <=, "
     ">, >=, !=), found 'L = 1'"),
    ("condition unreadable", "variants:\n  draw:\n    L: {choices: [1 m]}\n  require: [L > (1]\n",
     "p.yaml:21:13: variants.require[0]: expected a condition 'left < right': expected a "
     "complete expression"),
    ("condition on unknown name", "variants:\n  draw:\n    L: {choices: [1 m]}\n  require: [Lx > 1]\n",
     "p.yaml:21:13: variants.require[0]: expected a given in the condition (theta, L, theta', "
     "theta''), found 'Lx'; did you mean 'L'?"),
    ("condition on no drawn given", "variants:\n  draw:\n    L: {choices: [1 m]}\n  require: [theta > 0]\n",
     "p.yaml:21:13: variants.require[0]: expected a condition on a drawn given (L), found "
     "'theta > 0'"),
    ("bound on unknown name", "variants:\n  draw:\n    L: {choices: [1 m]}\n  bounds: {sped: {min: 0}}\n",
     "p.yaml:21:18: variants.bounds.sped: expected an objective, coordinate, rate or "
     "parameter to bound, found 'sped'; did you mean 'speed'?"),
    ("bound reversed", "variants:\n  draw:\n    L: {choices: [1 m]}\n  bounds: {speed: {min: 2 m/s, max: 1 m/s}}\n",
     "p.yaml:21:19: variants.bounds.speed: expected min <= max, found 2 > 1"),
    ("bound in another kind of unit", "variants:\n  draw:\n    L: {choices: [1 m]}\n  bounds: {speed: {min: 2 m/s, max: 1 s}}\n",
     "p.yaml:21:37: variants.bounds.speed.max: expected a value in units like m/s (the unit of "
     "'speed'), found '1 s'"),
    ("bound on a rate in another kind of unit", "variants:\n  draw:\n    L: {choices: [1 m]}\n  bounds: {\"theta'\": {max: 2 m}}\n",
     "p.yaml:21:28: variants.bounds.theta'.max: expected a value in units like rad/s (the unit "
     "of \"theta'\"), found '2 m'"),
    ("bound unreadable", "variants:\n  draw:\n    L: {choices: [1 m]}\n  bounds: {speed: {min: fast}}\n",
     "p.yaml:21:25: variants.bounds.speed.min: expected a number followed by a unit"),
    ("empty bound", "variants:\n  draw:\n    L: {choices: [1 m]}\n  bounds: {speed: {}}\n",
     "p.yaml:21:19: variants.bounds.speed: expected at least 1 field(s), found an empty "
     "mapping"),
]


@pytest.mark.parametrize("name, section, message", CASES, ids=[c[0] for c in CASES])
def test_bad_variants_give_one_located_message(name, section, message):
    error = error_of(with_variants(section))
    assert error.startswith(message)
    assert "\n" not in error


def test_a_statement_placeholder_names_a_given():
    text = with_variants("variants:\n  draw:\n    L: {choices: [1 m]}\n", "Length {Lx}.")
    assert error_of(text) == ("p.yaml:3:12: statement: expected a given between braces in the "
                              "statement (theta, L, theta', theta''), found '{Lx}'; did you "
                              "mean 'L'?")


def test_a_statement_that_writes_a_drawn_givens_own_value_is_refused():
    # every student's sheet would give the book's length beside their own
    text = with_variants("variants:\n  draw:\n    L: {choices: [1 m, 3 m]}\n",
                         "A pendulum of length 2 m turns about O.")
    assert error_of(text) == ("p.yaml:3:12: statement: expected {L} where the statement gives "
                              "the drawn value of L (each student's own), found its reference "
                              "value '2 m'")
    for fine in ("A pendulum of length {L} turns about O.",  # the student's value
                 "A pendulum of length 12 m turns about O.",  # another number
                 "A pendulum of length {L} (2 m in the book) turns about O."):
        load_problem_text(with_variants("variants:\n  draw:\n    L: {choices: [1 m, 3 m]}\n",
                                        fine), "p.yaml")


def test_every_error_of_the_section_is_reported_at_once():
    text = with_variants("variants:\n  draw:\n    Lx: {choices: [1 m]}\n"
                         "    L: {from: 2 m, to: 1 m, step: 1 m}\n")
    assert error_of(text).count("\n") == 1
