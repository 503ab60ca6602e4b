"""A mistaken model that changes only numbers is the right model with other parameter values;
any other change, or a parameter the change cannot be confined to, is no revaluation."""

from __future__ import annotations

from dataclasses import replace

import sympy as sp

from mechgrade.expressions.syntax import Call, Name, parse
from mechgrade.mechanics.dynamics_mutations import dynamics_mutations, unchanged_copy
from mechgrade.mechanics.revalue import common_models, revaluation
from mechgrade.spec.language import FUNCTIONS
from mechgrade.spec.model import Expr, ObjectiveKind
from library import library_problem


def _expr(text: str) -> Expr:
    return Expr(text, parse(text, functions=FUNCTIONS))


def _copies(name: str):
    problem = library_problem(name)
    return unchanged_copy(problem), {m.code: m.problem for m in dynamics_mutations(problem)
                                     if m.problem is not None}


def test_the_mass_written_for_the_weight_is_the_model_with_g_worth_one():
    base, copies = _copies("ladder_wall_lift_off")
    assert revaluation(base, copies["mass_for_weight"]) == (("g", 1),)
    g, m = sp.symbols("g m", positive=True)
    assert revaluation(base, copies["weight_for_mass"]) == (("g", 1), ("m", g * m))


def test_the_weight_left_out_is_the_model_with_g_worth_zero():
    base, copies = _copies("ladder_wall_lift_off")
    assert revaluation(base, copies["weight_omitted"]) == (("g", 0),)


def test_a_plastic_impact_read_for_an_elastic_one_is_the_model_with_e_worth_zero():
    base, _ = _copies("rod_strikes_ledge")
    ignored = [m.problem for m in dynamics_mutations(library_problem("rod_strikes_ledge"))
               if m.code == "restitution_ignored"]
    assert [revaluation(base, c) for c in ignored] == [(("e", 1),), (("e", 0),)]


def test_a_load_moved_changes_the_model_not_its_numbers():
    base, copies = _copies("ladder_wall_lift_off")
    assert revaluation(base, copies["load_at_other_point"]) is None  # a point, not a number


def test_a_parameter_read_by_a_numeric_objective_is_not_revalued():
    base, copies = _copies("ladder_wall_lift_off")
    weight = replace(base.objectives[0], id="weight", find=_expr("m*g"), unit="N",
                     kind=base.objectives[2].kind)
    reads_g = replace(base, objectives=base.objectives + (weight,))
    mistaken = copies["mass_for_weight"]
    assert revaluation(reads_g, replace(mistaken, objectives=mistaken.objectives + (weight,))
                       ) is None


def test_a_factor_that_varies_with_the_motion_is_no_revaluation():
    base, _ = _copies("ladder_wall_lift_off")
    d = base.dynamics
    assert d is not None and d.gravity is not None
    varying = replace(base, dynamics=replace(d, gravity=_expr(f"theta*({d.gravity.text})")))
    assert revaluation(base, varying) is None


def test_copies_that_differ_only_in_numbers_share_one_model():
    problem = library_problem("rod_strikes_ledge")
    copies = tuple(m.problem for m in dynamics_mutations(problem)
                   if m.code == "restitution_component")
    shared = common_models(problem, copies)
    assert all(s is not None and s[0] is shared[0][0] for s in shared)
    common = shared[0][0]
    # each contact's coefficient a parameter of its own, of either sign
    assert [(q.name, q.positive) for q in common.parameters[-2:]] == [
        ("mistaken_0", False), ("mistaken_1", False)]


def test_a_force_taken_at_two_other_points_is_one_model_with_both_versions():
    # the ladder's weight at A, or at B: each version times its own factor, 1 or 0
    problem = library_problem("ladder_wall_lift_off")
    moved = tuple(m.problem for m in dynamics_mutations(problem)
                  if m.code == "load_at_other_point")
    (common, at_a), (same, at_b) = common_models(problem, moved)
    assert common is same
    assert [(f.name, f.at, f.force.text) for f in common.dynamics.forces] == [
        ("mistaken_weight~ladder~0", "A", "mistaken_0*(((m))*(-g*N.y))"),
        ("mistaken_weight~ladder~1", "B", "mistaken_1*(((m))*(-g*N.y))")]
    assert at_a == (("mistaken_0", 1), ("mistaken_1", 0))
    assert at_b == (("mistaken_0", 0), ("mistaken_1", 1))


def test_copies_that_differ_in_a_vector_or_a_named_force_s_point_are_each_their_own_model():
    problem = library_problem("ladder_wall_lift_off")
    moved = tuple(m.problem for m in dynamics_mutations(problem)
                  if m.code == "load_at_other_point")
    # a force an objective reads by its name is not split in two
    name = moved[0].dynamics.forces[0].name
    reads = replace(moved[0].objectives[0], id="weight",
                    find=Expr(f"force({name})", Call("force", (Name(name),))),
                    kind=ObjectiveKind.VECTOR, frame="N", unit="N")
    reading = tuple(replace(m, objectives=m.objectives + (reads,)) for m in moved)
    assert common_models(problem, reading) == (None, None)
    base = unchanged_copy(problem)
    d = base.dynamics
    sideways = replace(base, dynamics=replace(d, gravity=_expr("g*N.x")))
    assert common_models(problem, (base, sideways)) == (None, None)


def test_the_names_of_a_shared_model_s_numbers_are_nobody_else_s():
    problem = library_problem("rod_strikes_ledge")
    taken = replace(problem, parameters=problem.parameters + (
        replace(problem.parameters[0], name="mistaken_0"),))
    copies = tuple(m.problem for m in dynamics_mutations(problem)
                   if m.code == "restitution_component")
    ((_, values), *_) = common_models(taken, copies)
    assert [name for name, _ in values] == ["mistaken__0", "mistaken__1"]
