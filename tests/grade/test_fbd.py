"""Free-body diagrams written as text, judged against the model's (mechgrade.grade.fbd)."""

from __future__ import annotations

import dataclasses
import math
import random
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mechgrade.grade.fbd import LoadMistake, _inside, judge_diagram, read_diagram
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
    assert judged.rows[0].mistakes == (LoadMistake.WRONG_DIRECTION,)


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


def test_a_diagram_too_long_or_with_too_many_unknowns_is_refused(incline, pendulum):
    with pytest.raises(Exception, match="at most 4000 characters"):
        read_diagram("w: m g j;" * 500, incline, "block")
    with pytest.raises(Exception, match=r"found 22 .a load at several points counts once"):
        read_diagram("w at G, O: m g j;" * 11, pendulum, "rod")
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


def own_diagram_failures(instant, body: str, draw) -> list[str]:
    """The model's own diagram of ``body`` rewritten in conventions ``draw`` picks (order,
    frame, signs of unknowns, names or words), then with each single seeded error (a load
    dropped, doubled, reversed, moved): what the judge got otherwise than expected.
    ``draw(options)`` picks one of ``options``."""
    diagram = instant.diagram(body)
    if not instant.values or any(vectors is None for _, vectors in instant.frames):
        # solved symbolically only, or where the model has no state: nothing to judge at
        verdict = judge_diagram("weight: -m g j", instant, body).verdict
        return [] if verdict == "not_evaluated" else [f"no instant, judged {verdict}"]
    order = list(range(len(diagram.loads)))
    for i in range(len(order) - 1, 0, -1):  # a shuffle by draw, so that hypothesis shrinks it
        j = draw(range(i + 1))
        order[i], order[j] = order[j], order[i]
    frame = draw([name for name, vectors in instant.frames if vectors is not None])
    flip, word = draw([False, True]), draw([False, True])
    names = iter(f"U{n}" for n in range(100))
    loads = [diagram.loads[i] for i in order]
    if any(load.vector is None for load in loads):
        return []  # nothing to judge against at this instant
    texts = [_written(load, instant, frame, flip, word, names) for load in loads]
    failures = []

    def judged(parts):
        return judge_diagram("; ".join(parts), instant, body)

    right = judged(texts)
    if right.verdict != "correct":
        failures.append(f"right diagram: {right.assessment.feedback} ({'; '.join(texts)})")
    for k, load in enumerate(loads):
        if len(texts) == 1:  # nothing left: no answer
            if judged([]).verdict != "missing":
                failures.append(f"{load.name} dropped: {judged([]).assessment.feedback}")
            continue
        dropped = judged(texts[:k] + texts[k + 1:])
        if [row.load for row in dropped.rows if row.mistakes] != [load.name]:
            failures.append(f"{load.name} dropped: {dropped.assessment.feedback}")
        doubled = judged(texts + [texts[k]])
        if [row.mistakes for row in doubled.rows if row.mistakes] != [(LoadMistake.EXTRA,)]:
            failures.append(f"{load.name} doubled: {doubled.assessment.feedback}")
        label, vector = texts[k].split(":", 1)
        if not load.unknown and math.hypot(*load.vector) > 1e-6 * _largest(diagram):
            wrong = _wrong(judged(texts[:k] + [f"{label}: -({vector})"] + texts[k + 1:]))
            if wrong != [(load.name, (LoadMistake.REVERSED,))]:
                failures.append(f"{load.name} reversed: {wrong}")
        here = instant.point(load.point) if load.point else None
        elsewhere = [p for p, r in instant.points if r is not None and here is not None
                     and math.dist(r, here) > 1e-6]
        if diagram.frame is not None and elsewhere:
            moved = f"{label.split(' at ')[0]} at {draw(elsewhere)}:{vector}"
            wrong = _wrong(judged(texts[:k] + [moved] + texts[k + 1:]))
            if not any(name == load.name and LoadMistake.WRONG_POINT in mistakes
                       for name, mistakes in wrong):
                failures.append(f"{load.name} moved: {wrong}")
    return failures


def _largest(diagram) -> float:
    return max((math.hypot(*load.vector) for load in diagram.loads if load.vector), default=1.0)


def _wrong(judged):
    """The rows with mistakes (a load's name may be several loads': parts' weights, a cord
    pulling at two points, so a mistake is looked for by name among them)."""
    return [(row.load, row.mistakes) for row in judged.rows if row.mistakes]


@settings(max_examples=10, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_the_models_own_diagram_in_any_convention_is_right_and_each_seeded_error_named(
        incline, pendulum, data):
    instant, body = data.draw(st.sampled_from([(incline, "block"), (pendulum, "rod")]))
    assert own_diagram_failures(instant, body, lambda options: data.draw(
        st.sampled_from(list(options)))) == []


DYNAMICS = [path for path in sorted(PROBLEMS.glob("*.yaml"))
            if re.search(r"^bodies:", path.read_text(encoding="utf-8"), re.M)]


@pytest.mark.slow
@pytest.mark.parametrize("path", DYNAMICS, ids=lambda path: path.stem)
def test_every_dynamics_problems_own_diagrams_are_right_and_seeded_errors_named(path):
    problem = load_problem(path)
    instant = derivation_instant(problem, solve(problem))
    rng = random.Random(path.stem)
    for diagram in instant.diagrams:
        assert own_diagram_failures(instant, diagram.body,
                                    lambda options: rng.choice(list(options))) == []


def test_a_load_named_twice_by_its_model_name_is_extra_not_another_load(pendulum):
    judged = judge_diagram("gravity at G: -m g j; gravity at O: X i + Y j", pendulum, "rod")
    assert [(row.load, row.mistakes) for row in judged.rows] == [
        ("gravity", ()), ("R_O", (LoadMistake.MISSING,)), (None, (LoadMistake.EXTRA,))]


@pytest.fixture(scope="module")
def chain():
    return _instant("two_mass_spring_chain")


def test_two_loads_of_one_kind_are_paired_so_that_the_most_are_right(chain):
    # the reversed first spring (+10 i) is nearer the second one (+5 i) than its own (-10 i)
    judged = judge_diagram("spring 1: k1 (x1 - L1) i; spring 2: k2 (x2 - x1 - L2) i; "
                           "damper: c (x2' - x1') i", chain, "block1")
    assert [(row.load, row.mistakes) for row in judged.rows] == [
        ("s1", (LoadMistake.REVERSED,)), ("s2", ()), ("d", ())]
    assert judge_diagram("spring: k2 (x2 - x1 - L2) i; spring: -k1 (x1 - L1) i; "
                         "damper: c (x2d - x1d) i", chain, "block1").verdict == "correct"


@pytest.fixture(scope="module")
def pulley():
    return _instant("movable_pulley_two_blocks")


@pytest.mark.parametrize("text", [
    "weight at B: -mB g j; tension at B1, B2: T j",
    "T at B2 and B1: T j; gravity at B: -mB g j",
    "T at B1: T1 j; T at B2: T2 j; weight at B: -mB g j",
])
def test_one_cord_pulling_at_two_points_of_a_body_is_written_once_or_at_each(pulley, text):
    judged = judge_diagram(text, pulley, "blockB")
    assert judged.verdict == "correct", judged.assessment.feedback
    assert [(row.load, row.point) for row in judged.rows] == [
        ("gravity", "B"), ("T", "B1"), ("T", "B2")]


def test_a_cord_at_one_of_its_two_points_is_missing_at_the_other(pulley):
    judged = judge_diagram("weight at B: -mB g j; T at B2: T j", pulley, "blockB")
    assert [(row.point, row.mistakes) for row in judged.rows] == [
        ("B", ()), ("B1", (LoadMistake.MISSING,)), ("B2", ())]
    judged = judge_diagram("weight at B: -mB g j; T at B1, B2: -T j; T at B: T j", pulley,
                           "blockB")
    assert [(row.point, row.mistakes) for row in judged.rows] == [
        ("B", ()), ("B1", ()), ("B2", ()), ("B", (LoadMistake.EXTRA,))]


def test_a_point_named_twice_for_one_load_is_refused(pulley):
    with pytest.raises(Exception, match="expected each point of 'T' once, found 'B1' twice"):
        read_diagram("T at B1, B1: T j", pulley, "blockB")
    with pytest.raises(Exception, match=r"expected a point of the problem .*found 'Q'"):
        read_diagram("T at B1 and Q: T j", pulley, "blockB")


def test_a_problem_symbol_without_a_value_is_refused_not_taken_for_an_unknown(incline):
    unvalued = dataclasses.replace(
        incline, values=tuple((n, v) for n, v in incline.values if n != "m"), unvalued=("m",))
    with pytest.raises(Exception, match=r"found 'm' .* which the problem leaves without one"):
        read_diagram("weight: m g j; normal: N A.y; friction: -mu_k N A.x", unvalued, "block")
    assert incline.unvalued == ()


@pytest.mark.parametrize("columns", [[(0, 0, 1), (0, 0, 1), (1, 0, 0)],
                                     [(0, 1, 0), (0, 2, 0), (0, 0, 1)],
                                     [(1, 1, 0), (1, 1, 0), (0, 0, 1)]])
def test_directions_given_twice_still_span_every_direction_given(columns):
    # a direction repeated before another one: the span holds the other one too
    directions = np.array(columns, dtype=float).T
    assert _inside(directions, directions)
    assert not _inside(np.array([[1.0, -1.0, 0.0]]).T, directions)
