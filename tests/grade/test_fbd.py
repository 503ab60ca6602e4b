"""Free-body diagrams written as text, judged against the model's (mechgrade.grade.fbd)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mechgrade.grade.fbd import LoadMistake, judge_diagram, read_diagram
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.solve.derivation import derivation_instant
from mechgrade.spec import load_problem

PROBLEMS = shipped_dir("problems")


def _instant(name: str):
    problem = load_problem(PROBLEMS / f"{name}.yaml")
    return derivation_instant(problem, solve(problem))


@pytest.fixture(scope="module")
def incline():
    return _instant("block_sliding_down_incline")


@pytest.fixture(scope="module")
def pendulum():
    return _instant("pendulum_pin_reaction")


@pytest.mark.parametrize("text", [
    "weight: -m g j; normal: N A.y; friction: -mu_k N A.x",
    "friction: -mu_k N A.x; normal: N A.y; weight: -m g j",  # the unknown bound by the normal
    "W: -mg ĵ; N_P: -R A.y; F_P: mu_k R A.x",  # names of the student's and the model's
    "gravity at P: m g sin(β) A.x - m g cos(β) A.y\nnormal force at P: n A.y\n"
    "kinetic friction at P: -μ_k n A.x",
    "weight: -39.24 j; normal: 33.98 A.y; friction: -8.496 A.x",  # numbers, in SI
])
def test_a_right_diagram_is_right_in_any_convention(incline, text):
    judged = judge_diagram(text, incline, "block")
    assert (judged.verdict, judged.credit) == ("correct", 1.0), judged.assessment.feedback


def test_a_label_of_the_students_own_is_matched_by_where_the_load_acts(pendulum):
    judged = judge_diagram("W at G: -m g j; R at O: X i + Y j", pendulum, "rod")
    assert judged.verdict == "correct"
    assert [row.load for row in judged.rows] == ["gravity", "R_O"]


def test_each_mistake_is_named_on_its_own_row(incline):
    judged = judge_diagram("weight: -2 m g j; normal: N j; friction: mu_k N A.x; "
                           "centripetal force: m xd^2 A.y", incline, "block")
    assert [(row.label, row.mistakes) for row in judged.rows] == [
        ("weight", (LoadMistake.WRONG_MAGNITUDE,)), ("normal", (LoadMistake.WRONG_DIRECTION,)),
        ("friction", (LoadMistake.REVERSED,)), ("centripetal force", (LoadMistake.EXTRA,))]
    assert judged.verdict == "incorrect" and judged.credit == 0.0
    assert "the centripetal force is the resultant of the loads" in judged.assessment.feedback


def test_a_load_turned_by_an_angle_has_the_wrong_direction(incline):
    judged = judge_diagram("weight: -m g A.y; normal: N A.y; friction: -mu_k N A.x",
                           incline, "block")
    assert [row.mistakes for row in judged.rows][0] == (LoadMistake.WRONG_DIRECTION,)


def test_a_rigid_bodys_force_needs_its_point_and_a_particles_does_not(incline, pendulum):
    assert judge_diagram("weight at P: -m g j; normal: N A.y; friction: -mu_k N A.x",
                         incline, "block").verdict == "correct"
    judged = judge_diagram("weight: -m g j; pin at O: Ox i + Oy j", pendulum, "rod")
    assert judged.rows[0].mistakes == (LoadMistake.WRONG_POINT,)
    assert "say where it acts" in judged.rows[0].feedback


def test_a_reaction_with_a_direction_too_many_is_wrong(incline):
    judged = judge_diagram("weight: -m g j; normal: Nx i + Ny j; friction: -mu_k N A.x",
                           incline, "block")
    assert judged.rows[1].mistakes == (LoadMistake.WRONG_DIRECTION,)
    assert "1 unknown direction, you gave 2" in judged.rows[1].feedback


def test_a_diagram_not_given_is_missing_and_one_not_read_is_unreadable(incline):
    assert judge_diagram(None, incline, "block").verdict == "missing"
    assert judge_diagram("  ", incline, "block").verdict == "missing"
    judged = judge_diagram("weight: __import__('os')", incline, "block")
    assert judged.verdict == "unreadable" and judged.rows == ()


def test_a_diagram_too_long_or_with_too_many_unknowns_is_refused(incline):
    with pytest.raises(Exception, match="at most 4000 characters"):
        read_diagram("w: m g j;" * 500, incline, "block")
    many = "; ".join(f"f{n}: U{n} i" for n in range(13))
    with pytest.raises(Exception, match="at most 12 unknowns"):
        read_diagram(many, incline, "block")


def test_a_rate_that_is_not_the_problems_is_refused(incline):
    with pytest.raises(Exception, match="names of your own"):
        read_diagram("damper: -c z' i", incline, "block")


# ------------------------------------------------------------------ the model's own diagram


def _written(load, instant, frame: str, flip: bool, word: bool, names) -> str:
    """A model load as a student could write it: along ``frame``'s unit vectors, with unknowns
    of the student's own (drawn the other way when ``flip``)."""
    axes = [np.array(instant.unit_vector(frame, a)) for a in "xyz"]
    label = str(load.kind).split()[-1] if word else load.name
    at = f" at {load.point}" if load.point else ""

    def along(v) -> str:
        parts = [f"({float(np.dot(v, e))!r}) {frame}.{a}" for e, a in zip(axes, "xyz")]
        return " + ".join(parts)

    if load.unknown:
        sign = "-" if flip else ""
        terms = [f"{sign}{next(names)} ({along(d)})" for d in load.directions if d is not None]
        return f"{label}{at}: " + " + ".join(terms)
    return f"{label}{at}: {along(load.vector)}"


def _own_diagram(instant, body, order, frame, flip, word):
    diagram = instant.diagram(body)
    names = iter(f"U{n}" for n in range(100))
    loads = [diagram.loads[i] for i in order]
    return [_written(load, instant, frame, flip, word, names) for load in loads], loads


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_the_models_own_diagram_in_any_convention_is_right_and_each_seeded_error_named(
        incline, pendulum, data):
    instant, body = data.draw(st.sampled_from([(incline, "block"), (pendulum, "rod")]))
    diagram = instant.diagram(body)
    order = data.draw(st.permutations(range(len(diagram.loads))))
    frame = data.draw(st.sampled_from([name for name, _ in instant.frames]))
    texts, loads = _own_diagram(instant, body, order, frame, data.draw(st.booleans()),
                                data.draw(st.booleans()))
    assert judge_diagram("; ".join(texts), instant, body).verdict == "correct"
    k = data.draw(st.integers(0, len(loads) - 1))
    dropped = judge_diagram("; ".join(texts[:k] + texts[k + 1:]), instant, body)
    assert [row.load for row in dropped.rows if row.mistakes] == [loads[k].name]
    doubled = judge_diagram("; ".join(texts + [texts[k]]), instant, body)
    assert [row.mistakes for row in doubled.rows if row.mistakes] == [(LoadMistake.EXTRA,)]
    known = loads[k]
    if not known.unknown and math.hypot(*known.vector) > 0:
        label, vector = texts[k].split(":")
        reversed_ = texts[:k] + [f"{label}: -({vector})"] + texts[k + 1:]
        row = next(r for r in judge_diagram("; ".join(reversed_), instant, body).rows
                   if r.load == known.name)
        assert row.mistakes == (LoadMistake.REVERSED,)
    if diagram.frame is not None and loads[k].point is not None:
        elsewhere = [p for p, r in diagram.points if r != instant.point(loads[k].point)]
        label, vector = texts[k].split(":")
        moved = texts[:k] + [f"{label.split(' at ')[0]} at {elsewhere[0]}:{vector}"] + \
            texts[k + 1:]
        row = next(r for r in judge_diagram("; ".join(moved), instant, body).rows
                   if r.load == loads[k].name)
        assert LoadMistake.WRONG_POINT in row.mistakes
