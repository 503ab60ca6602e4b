"""The generated mistakes of a class of dynamics variants, worked out together, are those of
each variant worked out alone."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from mechgrade.errors import MechgradeError
from mechgrade.solve import solve
from mechgrade.mechanics.dynamics_mutations import dynamics_mutations, unchanged_copy
from mechgrade.solve.batch import _template, solve_variants
from mechgrade.solve.dynamics import kinetics_plan, share_kinetics, solve_dynamics
from mechgrade.solve.dynamics_mutants import _read_in_copy, _revalued
from mechgrade.spec import load_problem

DATA = Path(__file__).resolve().parents[1] / "data"
PROBLEMS = Path(__file__).resolve().parents[2] / "problems"


@pytest.mark.slow
def test_a_class_s_generated_mistakes_are_each_variant_s_alone():
    problem = load_problem(DATA / "variants" / "dynamics" / "pin_pendulum.yaml")
    variants = [{"m": 2.5, "L": 0.8}, {"m": 4.0, "L": 1.6}, {"m": 1.5, "L": 1.1}]
    together = solve_variants(problem, variants)
    for solution, givens in zip(together, variants):
        one = solve(problem, givens=givens)
        for a, b in zip(solution.results, one.results):
            assert [(m.code, m.message, m.expr, m.step) for m in a.generated_mistakes] == \
                [(m.code, m.message, m.expr, m.step) for m in b.generated_mistakes], a.id
            assert all(np.allclose(np.atleast_1d(x.value), np.atleast_1d(y.value),
                                   rtol=1e-8, atol=1e-10)
                       for x, y in zip(a.generated_mistakes, b.generated_mistakes)
                       if x.value is not None)


def test_a_variant_whose_event_never_happens_fails_in_the_class_not_alone():
    problem = load_problem(PROBLEMS / "block_slides_on_cart.yaml")
    never, slides = _template(problem).solve([{"mu": 0.0}, {"mu": 0.25}])
    assert never is not None and slides is not None  # neither was left to solve alone
    error = never if isinstance(never, MechgradeError) else never.failures[0].error
    assert str(error).endswith("does not happen within 60 s")


@pytest.mark.slow
def test_a_solution_sent_to_another_process_carries_its_mistakes_not_the_class_s_work():
    import pickle

    problem = load_problem(DATA / "variants" / "dynamics" / "pin_pendulum.yaml")
    first, _ = solve_variants(problem, [{"m": 2.5}, {"m": 3.0}])
    result = first.results[0]
    sent = pickle.loads(pickle.dumps(result))
    assert type(sent.generated_mistakes) is tuple
    assert list(sent.generated_mistakes) == list(result.generated_mistakes)


@pytest.mark.parametrize("name", ["atwood_machine", "block_on_turntable"])
def test_a_mistake_that_changes_only_numbers_has_its_own_model_s_values(name):
    # the unchanged copy shares the reference's plan: the turntable's too, its static
    # friction an unknown force without its bound
    problem = load_problem(PROBLEMS / f"{name}.yaml")
    for m in dynamics_mutations(problem):
        if m.code not in ("mass_for_weight", "weight_for_mass"):
            continue
        revalued = _revalued(problem, m.problem, [{}])
        assert revalued is not None, m.code
        ids = {o.id for o in m.problem.objectives if o.kind != "symbolic"}
        own = solve_dynamics(m.problem, objectives=ids)
        shared = solve_dynamics(revalued[0], givens=revalued[1][0], objectives=ids)
        for a, b in zip(own.results, shared.results):
            assert np.allclose(a.value, b.value, rtol=1e-9), (m.code, a.id)


def test_a_static_friction_taken_as_an_unknown_force_shares_the_reference_s_balances():
    problem = load_problem(PROBLEMS / "block_on_turntable.yaml")
    copy = unchanged_copy(problem)
    assert share_kinetics(copy, problem)
    plan = kinetics_plan(copy)
    assert plan.kin.balances is kinetics_plan(problem).kin.balances
    assert kinetics_plan(problem).bounds and not plan.bounds and not plan.kin.bounds
    # a copy with its weight left out is another model: not shared
    omitted = next(m.problem for m in dynamics_mutations(problem)
                   if m.code == "weight_omitted")
    assert not share_kinetics(omitted, problem)


def test_a_value_read_at_another_instant_of_the_motion_shares_the_reference_s_balances():
    # the ladder's values at the start (a moment after t = 0), not at its event: only the
    # event differs, the balances are the reference's and the values those of a derivation
    problem = load_problem(PROBLEMS / "ladder_wall_lift_off.yaml")
    copies = {m.code: m.problem for m in dynamics_mutations(problem) if m.problem}
    ids = {o.id for o in copies["value_at_start"].objectives}
    own = solve_dynamics(replace(copies["value_at_start"]), objectives=ids)  # derived
    start = _read_in_copy(problem, copies["value_at_start"])
    assert kinetics_plan(start).kin.balances is kinetics_plan(problem).kin.balances
    assert kinetics_plan(start).kin.until != kinetics_plan(problem).kin.until
    shared = solve_dynamics(start, objectives=ids)
    for a, b in zip(own.results, shared.results):
        assert np.allclose(a.value, b.value, rtol=1e-9), a.id
    # the weight moved to another point is another model: derived
    moved = _read_in_copy(problem, copies["load_at_other_point"])
    assert kinetics_plan(moved).kin.balances != kinetics_plan(problem).kin.balances


@pytest.mark.parametrize("name", ["ruina_9_24_momentum_projection", "pucks_oblique_impact"])
def test_rates_before_an_impact_mistaken_are_read_in_the_reference_s_balances(name):
    # a sign flipped, sin and cos exchanged, the impact taken head-on: the reference's
    # balances with other rates before (9.24's objectives read before(momentum) in them),
    # with the values of the copy's own derivation
    problem = load_problem(PROBLEMS / f"{name}.yaml")
    struck = [m.problem for m in dynamics_mutations(problem) if m.code in (
        "given_sign", "angle_complement", "impact_taken_head_on")]
    assert struck
    for copy in struck:
        ids = {o.id for o in copy.objectives if o.kind != "symbolic"}
        own = solve_dynamics(replace(copy), objectives=ids)  # derived
        read = kinetics_plan(_read_in_copy(problem, copy)).kin
        assert read.written is kinetics_plan(problem).kin.written
        derived = kinetics_plan(replace(copy)).kin
        assert read.balances == derived.balances  # as written up
        assert read.objectives == derived.objectives
        shared = solve_dynamics(copy, objectives=ids)
        for a, b in zip(own.results, shared.results):
            assert np.allclose(a.value, b.value, rtol=1e-9, atol=1e-12), a.id


def test_mistakes_that_differ_only_in_numbers_have_their_own_models_values_in_one_model():
    # the rod's three ways of putting e on the tangential component: one derivation
    problem = load_problem(PROBLEMS / "rod_strikes_ledge.yaml")
    variants = [{}, {"e": 0.8, "v0": 3.0}]
    for m in dynamics_mutations(problem):
        if m.code != "restitution_component":
            continue
        common, givens = _revalued(problem, m.problem, variants)
        ids = {o.id for o in m.problem.objectives if o.kind != "symbolic"}
        for variant, shared_givens in zip(variants, givens):
            own = solve_dynamics(m.problem, givens=variant, objectives=ids)
            shared = solve_dynamics(common, givens=shared_givens, objectives=ids)
            for a, b in zip(own.results, shared.results):
                assert np.allclose(a.value, b.value, rtol=1e-9, atol=1e-12), (m.code, a.id)


def test_a_positive_parameter_made_negative_is_solved_as_its_own_model():
    problem = load_problem(PROBLEMS / "block_sliding_down_incline.yaml")
    reversed_ = next(m for m in dynamics_mutations(problem) if m.code == "friction_reversed")
    assert reversed_.problem is not None
    assert _revalued(problem, reversed_.problem, [{}]) is None  # mu_k -> -mu_k


def test_a_given_linear_acceleration_taken_as_zero_leaves_the_static_force():
    # the cab speeding up at y'' = 2 ft/s^2: with it taken as zero the cable holds the weight
    problem = load_problem(PROBLEMS / "elevator_motor_power.yaml")
    (slip,) = [m for m in solve(problem).result("tension").generated_mistakes
               if m.code == "given_acceleration_zero"]
    assert float(np.ravel(slip.value)[0]) == pytest.approx(3000.0)  # lbf
    assert "given acceleration of y" in slip.message and "2 ft/s^2" in slip.message


def test_a_class_asked_only_symbolic_answers_reads_no_mistaken_reading_or_term():
    from mechgrade.solve.dynamics_mutants import ClassMistakes, _one_by_one

    problem = load_problem(PROBLEMS / "atwood_machine.yaml")
    solution = solve_dynamics(problem, objectives={"a1_symbolic"})
    asked = []

    def together(mistaken, givens, objectives):
        asked.append(set(objectives))
        return _one_by_one(solve_dynamics)(mistaken, givens, objectives)

    first, _ = ClassMistakes(problem, [{}, {}], together).attached([solution, solution])
    assert first.result("a1_symbolic").generated_mistakes  # the mistaken models' answers
    assert asked and not any("~" in oid for ids in asked for oid in ids)


def test_a_shared_plan_lasts_as_long_as_its_copy_not_as_long_as_256_other_shares():
    # a mistaken copy kept by a cache must not be derived in full again after many others
    import copy
    import gc

    from mechgrade.solve import dynamics

    problem = load_problem(PROBLEMS / "block_on_turntable.yaml")
    kept = copy.copy(unchanged_copy(problem))
    assert share_kinetics(kept, problem)
    others = [copy.copy(kept) for _ in range(300)]
    assert all(share_kinetics(other, problem) for other in others)
    assert kinetics_plan(kept).kin.balances is kinetics_plan(problem).kin.balances
    before = len(dynamics._SHARED)
    del others
    gc.collect()
    assert len(dynamics._SHARED) == before - 300  # a copy's death frees its plan


def test_a_class_keeps_the_results_made_with_its_mistakes_and_attaches_them_to_the_others():
    from mechgrade.solve.dynamics_mutants import ClassMistakes, _one_by_one
    from mechgrade.solve.result import ObjectiveResult, Solution

    problem = load_problem(PROBLEMS / "pendulum_pin_reaction.yaml")
    solution = solve_dynamics(problem, objectives={"alpha"})
    mistakes = ClassMistakes(problem, [{}, {}, {}], _one_by_one(solve_dynamics))
    made = Solution(**{**vars(solution), "results": tuple(
        ObjectiveResult(**{**vars(r), "plausible": mistakes.plausible,
                           "generated_mistakes": mistakes.of(0, r.id)})
        for r in solution.results)})
    error = MechgradeError("not solved")
    kept, missed, attached = mistakes.attached([made, error, solution])
    assert kept is made and missed is error  # made once, with them
    assert attached.result("alpha").plausible == mistakes.plausible
    mine = [(m.code, m.value) for m in attached.result("alpha").generated_mistakes]
    assert mine == [(m.code, m.value) for m in kept.result("alpha").generated_mistakes]
    assert ("mass_for_weight", pytest.approx(-0.8, abs=0.01)) in [
        (code, round(value, 2)) for code, value in mine]
