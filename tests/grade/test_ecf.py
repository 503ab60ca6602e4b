"""Error carried forward from a vector step (grade/ecf.py): the given rates that give the
student's vector exactly, or the feedback saying why none are used. A stand-in solver makes
the vector a known function of the givens, so no problem is solved here."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from mechgrade.errors import SolveError
from mechgrade.grade.ecf import CarriedForward
from mechgrade.grade.policy import GradingPolicy
from mechgrade.grade.run import PlannedObjective
from mechgrade.resources import shipped_dir
from mechgrade.solve.result import ObjectiveResult
from mechgrade.spec import load_problem

CHAIN = load_problem(shipped_dir("problems") / "two_mass_spring_chain.yaml")
UPSTREAM = ObjectiveResult("v", "vector", "m/s", (1.0, 0.0, 0.0), frame="N")


def _carried(vector):
    """ECF whose re-solves give ``vector(givens)`` for the upstream objective 'v'."""
    def resolve(problem, givens):
        value = vector({**{g.key.text: g.si for g in problem.givens}, **givens})
        return SimpleNamespace(result=lambda _: SimpleNamespace(value=value))
    plan = SimpleNamespace(problems=[CHAIN], solutions=[SimpleNamespace(result=lambda _: UPSTREAM)])
    item = PlannedObjective(CHAIN, CHAIN.objectives[0], UPSTREAM, 1.0)
    return CarriedForward(GradingPolicy(), judging=None, resolve=resolve), plan, item


def test_the_rates_that_give_a_students_vector_exactly_replace_the_given_ones():
    ecf, plan, item = _carried(lambda g: (2 * g["x1'"], 3 * g["x1'"], 0.0))  # x1' = 0.5 m/s
    assert ecf.vector_givens(plan, item, "v", "(4, 6, 0) m/s") == pytest.approx({"x1'": 2.0})


@pytest.mark.parametrize("vector, text, feedback", [
    (lambda g: (2 * g["x1'"], 3 * g["x1'"], 0.0), "(4, 5, 0) m/s",
     "is not one the model can have with other values of x1': none gives it exactly."),
    (lambda g: (g["x1'"] + g["x2'"], 0.0, 0.0), "(4, 0, 0) m/s",
     "does not fix x1', x2': more than one set of them gives it."),
    (lambda g: (1.0, 0.0, 0.0), "(4, 0, 0) m/s",
     "does not change with any given rate of the problem."),
    (lambda g: (2 * g["x1'"], 0.0, 0.0), "4 m/s", "could not be read as a vector in its own "
                                                  "frame's unit vectors."),
])
def test_a_vector_no_single_set_of_rates_gives_exactly_is_not_carried_forward(vector, text,
                                                                             feedback):
    ecf, plan, item = _carried(vector)
    assert ecf.vector_givens(plan, item, "v", text) == (
        f"Error carried forward could not be applied: your answer to 'v' {feedback}")


def test_a_vector_the_model_cannot_recompute_is_not_carried_forward():
    def unsolvable(g):
        if g["x1'"] != 0.5:
            raise SolveError("no instant there")
        return (2 * g["x1'"], 0.0, 0.0)

    ecf, plan, item = _carried(unsolvable)
    assert ecf.vector_givens(plan, item, "v", "(4, 0, 0) m/s") == (
        "Error carried forward could not be applied: your answer to 'v' cannot be recomputed "
        "with another x1'.")
    ecf, plan, item = _carried(lambda g: (_ for _ in ()).throw(SolveError("no instant")))
    assert ecf.vector_givens(plan, item, "v", "(4, 0, 0) m/s") == (
        "Error carried forward could not be applied: your answer to 'v' cannot be recomputed "
        "at the problem's givens.")


def test_two_rates_that_move_the_vector_alike_but_for_a_re_solves_rounding_are_not_fixed():
    # x1' and x2' move v along one direction; the 1e-12 term is the rounding a numeric
    # re-solve leaves, no second direction: any split of the rates gives the vector
    ecf, plan, item = _carried(lambda g: (0.8 * (g["x1'"] + g["x2'"]) + 1e-12 * g["x2'"] ** 2,
                                          0.6 * (g["x1'"] + g["x2'"]), 0.0))
    assert ecf.vector_givens(plan, item, "v", "(4, 3, 0) m/s") == (
        "Error carried forward could not be applied: your answer to 'v' does not fix x1', x2': "
        "more than one set of them gives it.")
