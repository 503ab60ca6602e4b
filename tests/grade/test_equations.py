"""Equations of motion written as equations (mechgrade.grade.equations)."""

from __future__ import annotations

import random
import re

import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mechgrade.grade.equations import LoadSlip, _naming, judge_equations, read_equations
from mechgrade.mechanics.dynamics import derive_kinetics, free_body_loads
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.solve.derivation import MotionSamples, motion_samples
from mechgrade.spec import load_problem

DYNAMICS = [path for path in sorted(shipped_dir("problems").glob("*.yaml"))
            if re.search(r"^bodies:", path.read_text(encoding="utf-8"), re.M)]


def _samples(name: str):
    problem = load_problem(shipped_dir("problems") / f"{name}.yaml")
    return motion_samples(problem, solve(problem))


@pytest.fixture(scope="module")
def incline():
    return _samples("block_sliding_down_incline")


@pytest.fixture(scope="module")
def pendulum():
    return _samples("pendulum_pin_reaction")


@pytest.fixture(scope="module")
def atwood():
    return _samples("atwood_machine")


# the incline's two balances, along the slope and across it, as terms (text, sign)
ALONG = [("m x''", -1), ("m g sin(β)", 1), ("μ_k N", -1)]
LOADS = [None, "the weight of block", "the kinetic friction F_P on block"]
"""The load each term of ALONG is of (``None``: the inertia term is no load)."""
ACROSS = [("N", 1), ("m g cos(β)", -1)]


def _equation(terms, scale: int) -> str:
    """``sum(sign * term) = 0`` written with the negative terms moved to the right side and
    every term scaled."""
    left = [f"({scale})*({t})" for t, sign in terms if sign > 0] or ["0"]
    right = [f"({scale})*({t})" for t, sign in terms if sign < 0] or ["0"]
    return " + ".join(left) + " = " + " + ".join(right)


@settings(max_examples=15, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(a=st.integers(1, 5), b=st.sampled_from([-3, -1, 2, 7]), combine=st.booleans(),
       dropped=st.integers(0, len(ALONG) - 1))
def test_rearranged_scaled_and_combined_equations_are_right_a_dropped_term_is_named(
        incline, a, b, combine, dropped):
    along = _equation(ALONG, a)
    across = _equation(ACROSS, b)
    if combine:  # the second equation replaced by the sum of both
        across = _equation([(f"{a}*({t})", s) for t, s in ALONG]
                           + [(f"({b})*({t})", s) for t, s in ACROSS], 1)
    assert judge_equations(f"{along}; {across}", incline).verdict == "correct"
    wrong = _equation([term for n, term in enumerate(ALONG) if n != dropped], a)
    judged = judge_equations(f"{wrong}; {_equation(ACROSS, b)}", incline)
    assert [row.right for row in judged.rows] == [False, True], judged.assessment.feedback
    # the load the dropped term was is named, whatever the equation's scale
    assert judged.rows[0].load == LOADS[dropped], judged.assessment.feedback
    assert judged.rows[0].load_mistake is (LoadSlip.MISSING if LOADS[dropped] else None)
    turned = _equation([(t, -sign if n == dropped else sign) for n, (t, sign) in enumerate(ALONG)],
                       a)
    (row, _) = judge_equations(f"{turned}; {_equation(ACROSS, b)}", incline).rows
    assert row.load == (LOADS[dropped] or None), row.feedback
    assert row.load_mistake is (LoadSlip.TURNED_ROUND if LOADS[dropped] else None)


def test_a_pendulums_moment_equation_and_its_sign(pendulum):
    assert judge_equations("m L^2/3 θ'' = -m g L/2 sin(θ)", pendulum).verdict == "correct"
    assert judge_equations("θ'' = -3 g sin(θ)/(2 L)", pendulum).verdict == "correct"
    for wrong in ("m L^2/3 θ'' = m g L/2 sin(θ)", "m L^2/12 θ'' = -m g L/2 sin(θ)",
                  "m L^2/3 θ'' = -m g L/2 cos(θ)"):
        assert judge_equations(wrong, pendulum).verdict == "incorrect", wrong


def test_an_equation_naming_an_unknown_alone_says_nothing(pendulum):
    judged = judge_equations("Ox = 0", pendulum)
    assert judged.verdict == "incorrect"
    assert "says nothing about the motion" in judged.assessment.feedback


@pytest.fixture(scope="module")
def launcher():
    problem = load_problem(shipped_dir("problems") / "spring_launcher_a_of_x.yaml")
    return problem, motion_samples(problem, solve(problem))


def test_a_right_equation_holds_at_an_integrations_event_where_the_loads_vanish(launcher):
    # the launch event (the spring at its free length): the solved state's accelerations
    # are the limit just before the event, off by that fraction, which is all of them there;
    # each state's are solved again from its own coordinates and rates
    for text in ("m x'' = -k x", "m x'' = -k (abs(L0 + x) - L0)", "x'' = -k x/m"):
        assert judge_equations(text, launcher[1]).verdict == "correct", text


@pytest.mark.parametrize("text, mistake", [
    ("m x'' = k x", "turned round"),  # the spring drawn pulling the puck back
    ("m x'' = 0", "missing"),  # no spring at all: true only where it has its free length
    ("m x'' = -2 k x", "doubled"),
])
def test_a_wrong_equation_is_caught_away_from_the_event_where_the_spring_is_slack(
        launcher, text, mistake):
    # judged right by hand: m x'' = -k x (x the deflection, the spring pushing the puck on);
    # at the event every term is nought, so the states judged at are along the motion too
    (row,) = judge_equations(text, launcher[1]).rows
    assert not row.right
    # the launcher's spring is named "spring": named once, not "the spring spring on puck"
    assert (row.load, row.load_mistake) == ("the spring on puck", mistake), row.feedback


def test_the_states_judged_at_are_spread_along_the_motion(launcher):
    problem, samples = launcher
    deflections = {round(samples.state(k)["x"], 6) for k in range(len(samples.states))}
    assert len(deflections) == 3 and min(deflections) < 0 < max(deflections)
    # so a seeded error in the spring's term is judged, not passed over as nought
    ((_, terms),) = model_equations(problem)[0]
    assert [load.name for load, _ in terms] == ["spring"]
    assert not _nought(terms[0][1], samples)


def test_without_a_solved_state_equations_are_not_evaluated():
    assert judge_equations("x'' = 0", None).verdict == "not_evaluated"
    assert judge_equations(None, None).verdict == "missing"


def test_too_many_equations_or_unknowns_are_refused(incline):
    with pytest.raises(Exception, match="at most 12 equations"):
        read_equations("; ".join(["x'' = 0"] * 13), incline)
    with pytest.raises(Exception, match="at most 12 unknowns"):
        read_equations(" + ".join(f"U{n}" for n in range(13)) + " = m x''", incline)
    with pytest.raises(Exception, match="names of your own"):
        read_equations("m z'' = 0", incline)


@pytest.mark.parametrize("text, term", [
    ("m x'' = m g sin(β) + μ_k N; N = m g cos(β)", "mu_k*N"),  # friction drawn downhill
    ("m x'' = -m g sin(β) - μ_k N; N = m g cos(β)", "-m*g*sin(beta)"),
    ("m x'' = m g sin(β) + μ_k m g cos(β)", "mu_k*m*g*cos(beta)"),
    ("m x'' = m g sin(β); N = m g cos(β)", None),  # a term dropped: no term to turn
    ("m x'' = m g sin(β) - μ_k N; N = -m g cos(β)", None),  # N or m g cos β: either
])
def test_a_wrong_equations_one_term_of_the_wrong_sign_is_named(incline, text, term):
    judged = judge_equations(text, incline)
    (wrong,) = [row for row in judged.rows if not row.right]
    assert wrong.reversed_term == term
    assert ("has the wrong sign" in wrong.feedback) == (term is not None)


def test_of_two_terms_either_could_have_the_wrong_sign_so_neither_is_named(pendulum):
    (row,) = judge_equations("m L^2/3 θ'' = m g L/2 sin(θ)", pendulum).rows
    assert not row.right and row.reversed_term is None


@pytest.mark.parametrize("text, load, how", [
    ("x'' = g sin(β)", "the kinetic friction F_P on block", "missing"),  # divided by m
    ("m x'' = -μ_k N; N = m g cos(β)", "the weight of block", "missing"),
    ("m x'' = m g sin(β) - μ_k m g", None, None),  # a term of the wrong size names no load
    ("N = m g; m x'' = m g sin(β) - μ_k N", None, None),
    # N along the slope: the normal force's or the weight's component across it, twice
    ("m x'' = m g sin(β) - μ_k N + 2 N; N = m g cos(β)", None, None),
])
def test_a_wrong_equation_names_the_load_it_leaves_out_or_none_when_no_one_load_fits(
        incline, text, load, how):
    (wrong,) = [row for row in judge_equations(text, incline).rows if not row.right]
    assert (wrong.load, wrong.load_mistake) == (load, how), wrong.feedback
    assert ((f"({load} is {how} from it)" if how == "missing" else "") in wrong.feedback)


@pytest.mark.parametrize("text, feedback", [
    ("m1 y'' = T; m2 y'' = m2 g - T",
     "m1*ydd = T: does not hold for the motion (the weight of block1 is missing from it)."),
    # the rope's tension acts on both blocks: the one whose balance has block 2's weight
    ("m1 y'' = T - m1 g; m2 y'' = m2 g + T",
     "m2*ydd = m2*g+T: does not hold for the motion (its term T has the wrong sign: the "
     "tension T on block2 is turned round in it)."),
    ("m1 y'' = T - m1 g; m2 y'' = m2 g",
     "m2*ydd = m2*g: does not hold for the motion (the tension T on block2 is missing from "
     "it)."),
])
def test_of_a_load_on_two_bodies_the_one_the_equation_is_about_is_named(atwood, text, feedback):
    assert judge_equations(text, atwood).assessment.feedback == feedback


@pytest.mark.parametrize("text, said", [
    ("m L^2/3 θ'' = 0", "(the weight of rod is missing from it)"),
    # either side's sign: no term is named, but the weight's moment is twice the misfit
    ("m L^2/3 θ'' = m g L/2 sin(θ)", "(the weight of rod is turned round in it)"),
])
def test_a_moment_equation_names_the_load_whose_moment_it_leaves_out(pendulum, text, said):
    assert judge_equations(text, pendulum).assessment.feedback.endswith(said + ".")


@pytest.mark.parametrize("text, feedback", [
    # block 2's loads (down positive) with block 1's mass
    ("m1 y'' = T - m1 g; m1 y'' = m2 g - T",
     "m1*ydd = m2*g-T: does not hold for the motion (the wrong body: the loads on block2 "
     "balanced against the m a of block1)."),
    ("m1 y'' = T - m1 g; m2 y'' = m1 g - T",
     "m2*ydd = m1*g-T: does not hold for the motion (the wrong body: the loads on block1 "
     "balanced against the m a of block2)."),
])
def test_an_equation_balancing_one_bodys_loads_against_anothers_motion_is_named(
        atwood, text, feedback):
    judged = judge_equations(text, atwood)
    assert judged.assessment.feedback == feedback
    assert judged.assessment.diagnosis == "an equation for " + feedback.split("(", 1)[1][:-2]


def test_a_moment_balance_about_the_pin_with_the_inertia_about_g_is_the_wrong_point(pendulum):
    (row,) = judge_equations("m L^2/12 θ'' = -m g L/2 sin(θ)", pendulum).rows
    assert row.balance == ("the wrong point: the moments about O balanced against the rate of "
                           "angular momentum about G")
    assert (row.load, row.reversed_term) == (None, None)


@pytest.mark.parametrize("text, verdict", [
    ("m1 y'' = -T - m1 g; m2 y'' = m2 g + T", "correct"),  # the tension's sign the student's
    ("m1 a = T - m1 g; m2 a = m2 g - T; a = y''", "correct"),  # an acceleration's own name
    # both tensions doubled hold with T half the rope's: an unknown is a reaction at its size
    ("m1 y'' = 2 T - m1 g; m2 y'' = m2 g - 2 T", "incorrect"),
])
def test_an_unknown_is_a_reaction_by_another_name_or_sign_not_another_size(atwood, text,
                                                                             verdict):
    assert judge_equations(text, atwood).verdict == verdict


@pytest.mark.parametrize("text", [
    "m1 y'' = T - m1 g; m2 y'' = m2 g - T",  # right: nothing to name
    "m1 y'' = T; m2 y'' = m2 g - T",  # a load left out is no other body's balance
    "m1 y'' = T - m1 g; m2 y'' = 2 m2 g - T",  # nor is a load doubled
])
def test_an_equation_that_is_no_misplaced_balance_names_none(atwood, text):
    assert all(row.balance is None for row in judge_equations(text, atwood).rows)


# ---------------------------------------------------------- the model's own equations, rewritten

_FORCE = re.compile(r"body (\w+): \w+\.([xyz]) force balance")
_MOMENT = re.compile(r"body (\w+): moment balance about (\w+) \(\w+\.([xyz]) component\)")
MISTAKES = (("dropped", 0, "missing"), ("reversed", -1, "turned round"),
            ("doubled", 2, "doubled"))
"""A seeded error: what is done to one load's term, its factor, and how it is to be named."""


def model_equations(problem):
    """The model's momentum balances, each as ``(m a side, [(load, its term)])`` in its plain
    symbols, then its acceleration constraints (no loads), and its reactions; ``None`` for an
    impact, or a model whose balances do not fix its reactions (a motor's power sets a
    tension)."""
    kin = derive_kinetics(problem)
    if kin.impact or len(kin.balances) + len(kin.constraints) < len(
            kin.k.qdd) + len(kin.reactions):
        return None  # an impact's balances are of impulses; some loads are set otherwise
    loads = free_body_loads(problem)
    points = {name: sp.Matrix(r) for name, r in kin.k.points}
    out = []
    for e in kin.balances:
        force, moment = _FORCE.fullmatch(e.label), _MOMENT.fullmatch(e.label)
        assert force or moment, e.label
        if force:
            axis = "xyz".index(force.group(2))
            terms = [(load, load.force[axis]) for load in loads
                     if load.body == force.group(1) and load.force is not None]
        else:
            centre, axis = points[moment.group(2)], "xyz".index(moment.group(3))
            terms = [(load, load.moment[axis] if load.force is None
                      else (points[load.point] - centre).cross(load.force)[axis])
                     for load in loads if load.body == moment.group(1)]
        # each load's term as the model has it (expanded, a spring's would be terms that
        # cancel, larger than it: a misfit of its size could pass for rounding)
        terms = [(load, t) for load, t in terms if sp.expand(t) != 0]
        out.append((sp.expand(sum((t for _, t in terms), sp.S.Zero) - e.expr), terms))
    out += [(sp.expand(e.expr), []) for e in kin.constraints]
    return out, kin.reactions


def _written(equation, rename, sign, scale, moved):
    """An equation as a student may write it: turned round (an axis the other way), scaled,
    the loads on the right or everything on the left, the reactions by names of their own."""
    inertia, terms = equation
    left = sign * scale * inertia
    right = sum((sign * scale * t for _, t in terms), sp.S.Zero)
    if moved:
        left, right = left - right, sp.S.Zero
    return left.subs(rename), right.subs(rename)


def _text(pair) -> str:
    return f"{sp.sstr(pair[0])} = {sp.sstr(pair[1])}"


def _nought(term, samples) -> bool:
    """Whether ``term`` is nought at every sampled state (no error in it can be seen)."""
    names = sorted(term.free_symbols, key=str)
    f = sp.lambdify(names, term, modules="numpy")
    values = [float(f(*(samples.state(k)[str(n)] for n in names)))
              for k in range(len(samples.states))]
    return all(abs(v) <= 1e-9 * max(1.0, *map(abs, samples.states[k]))
               for k, v in enumerate(values))


def own_equations_failures(problem, samples, draw, seeded=None) -> list[str]:
    """The model's own equations of ``problem`` rewritten in conventions ``draw`` picks
    (order, axes flipped, scaled, rearranged, two combined, the reactions by names and signs of
    their own), then with single seeded errors (a load's term dropped, reversed, doubled; all
    of them, or the one ``seeded`` picks from ``(equation, term, mistake)`` choices): what
    the judge got otherwise than expected. A seeded error is caught (the set is not right); in
    an equation without reactions it is that equation alone that is wrong, and the load and
    its mistake are named (a reaction's unknown of the student's own absorbs whatever the
    model's reactions can make up, so there no more is asked)."""
    found = model_equations(problem)
    if found is None:
        return []
    equations, reactions = found
    accelerations = set(derive_kinetics(problem).k.qdd)

    def _own(n: int) -> set:
        inertia, terms = equations[n]
        return {r for r in reactions if any(r in u.free_symbols and not _nought(u, samples)
                                            for u in (inertia, *(t for _, t in terms)))}

    # an equation without accelerations whose reactions no other has only names them: it
    # says nothing about the motion (docs/answers.md), and is not written
    def _reacting(n: int) -> set:
        inertia, terms = equations[n]
        return set(reactions) & set().union(inertia.free_symbols,
                                            *(t.free_symbols for _, t in terms))

    if any(symbol.name not in samples.names for inertia, terms in equations
           for u in (inertia, *(t for _, t in terms)) for symbol in u.free_symbols
           if symbol not in reactions):
        return []  # the time of a driven motion: no symbol a student may write

    def _moving(n: int) -> bool:
        return any(not _nought(sp.diff(equations[n][0], a), samples) for a in accelerations)

    kept = [n for n in range(len(equations))
            if _moving(n) or not _reacting(n)
            or _reacting(n) & set().union(*(_reacting(m) for m in range(len(equations))
                                            if m != n))]
    equations = [equations[n] for n in kept]
    if len(equations) > 12:  # more than an answer may hold (MAX_EQUATIONS)
        return []
    rename = {r: draw([1, -1]) * sp.Symbol(f"U{n}") for n, r in enumerate(reactions)}
    conventions = [(draw([1, -1]), draw([1, 2, 3]), draw([False, True])) for _ in equations]
    pairs = [_written(e, rename, *c) for e, c in zip(equations, conventions)]
    order = list(range(len(pairs)))
    for i in range(len(order) - 1, 0, -1):  # a shuffle by draw, so that hypothesis shrinks it
        j = draw(range(i + 1))
        order[i], order[j] = order[j], order[i]

    def judged(written):
        return judge_equations("; ".join(map(_text, written)), samples)

    failures = []
    right = judged([pairs[i] for i in order])
    if right.verdict != "correct":
        failures.append(f"right: {right.assessment.feedback}")
    if len(pairs) > 1:
        a = draw(range(len(pairs)))
        b = draw([n for n in range(len(pairs)) if n != a])
        combined = list(pairs)
        combined[a] = (pairs[a][0] + pairs[b][0], pairs[a][1] + pairs[b][1])
        combination = judged(combined)
        # a combination may outgrow what the parser reads (MAX_NODES): refused, not judged
        if combination.verdict != "correct" and "expected an expression of at most" not in \
                combination.assessment.feedback:
            failures.append(f"{a} + {b} combined: {combination.assessment.feedback}")
    choices = [(e, t, m) for e, (_, terms) in enumerate(equations) for t in range(len(terms))
               for m in MISTAKES]
    for e, t, (what, factor, named) in choices if seeded is None else [seeded(choices)]:
        inertia, terms = equations[e]
        load = terms[t][0]
        if _nought(terms[t][1], samples) or _own(e) - set().union(
                *(_own(n) for n in range(len(equations)) if n != e)):
            # nought at every state judged at (a pendulum at rest hanging down), or the
            # equation has a reaction no other has: it only names it, whatever its size
            continue
        wrong = list(pairs)
        wrong[e] = _written((inertia, [(other, factor * u if s == t else u)
                                       for s, (other, u) in enumerate(terms)]),
                            rename, *conventions[e])
        judgement = judged(wrong)
        said = f"{load.name} {what} in {_text(wrong[e])}: {judgement.assessment.feedback}"
        if judgement.verdict == "correct":
            failures.append(f"not caught: {said}")
        elif not (inertia.free_symbols | terms[t][1].free_symbols) & set(reactions) and not any(
                u.free_symbols & set(reactions) for _, u in terms):
            rows = [(row.right, row.load, row.load_mistake) for row in judgement.rows]
            if rows != [(n != e, _naming(load) if n == e else None,
                         named if n == e else None) for n in range(len(wrong))]:
                failures.append(f"not named: {said}")
    return failures


@pytest.fixture(scope="module")
def own(atwood):
    """Two problems' models and motions: the Atwood machine (a rope's tension, an unknown in
    both balances) and the spring chain (no reactions: every seeded error is named)."""
    chain = load_problem(shipped_dir("problems") / "two_mass_spring_chain.yaml")
    return [(load_problem(shipped_dir("problems") / "atwood_machine.yaml"), atwood),
            (chain, motion_samples(chain, solve(chain)))]


@settings(max_examples=4, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_the_models_own_equations_in_any_convention_are_right_and_a_seeded_error_named(
        own, data):
    problem, samples = data.draw(st.sampled_from(own))

    def draw(options):
        return data.draw(st.sampled_from(list(options)))

    assert own_equations_failures(problem, samples, draw, seeded=draw) == []


OWN_EQUATIONS_LIMITS: dict[str, str] = {}
"""Problems the judge is known to get wrong, and why (strict: one put right fails)."""


@pytest.mark.slow
@pytest.mark.parametrize("path", [
    pytest.param(path, marks=pytest.mark.xfail(reason=OWN_EQUATIONS_LIMITS[path.stem],
                                               strict=True))
    if path.stem in OWN_EQUATIONS_LIMITS else path for path in DYNAMICS],
    ids=lambda path: path.stem)
def test_every_dynamics_problems_own_equations_are_right_and_seeded_errors_named(path):
    problem = load_problem(path)
    samples = motion_samples(problem, solve(problem))
    if samples is None:  # nothing solved numerically: nothing to judge at
        assert judge_equations("x'' = 0", None).verdict == "not_evaluated"
        return
    rng = random.Random(path.stem)
    assert own_equations_failures(problem, samples,
                                  lambda options: rng.choice(list(options))) == []


@pytest.mark.parametrize("unit", [1.0, 1e-3])  # in N, or divided by 1000 (in kN)
def test_equations_that_repeat_one_balance_leave_an_acceleration_undetermined_in_any_unit(unit):
    # a 20,000 t ship and its barge pushed together: the second equation is the first tripled,
    # so x'' and y'' are not both fixed; in N their slopes (~1e7) round by more than 1e-9
    ship = MotionSamples(("m", "g"), ("xdd", "ydd"), (),
                         ((2e7, 9.81, -3.27, -6.54), (2.2e7, 9.81, -3.27, -6.54)))
    text = (f"{unit} m x'' + {unit} m y'' = -{unit} m g; "
            f"{3 * unit} m x'' + {3 * unit} m y'' = -{3 * unit} m g")
    judged = judge_equations(text, ship)
    assert not judged.complete
    assert "do not determine x'', y''" in judged.assessment.feedback
