"""Many variants solved together give what solving each alone gives: answers, generated
mistakes with their messages, solved state, freedoms, warnings and errors."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from mechgrade.errors import MechgradeError
from mechgrade.expressions.syntax import Name, to_text
from mechgrade.grade.variants import draw_variant
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.solve.batch import _solved_together, _template, solve_variants
from mechgrade.solve.instant import answer_alone
from mechgrade.solve.result import Solution
from mechgrade.spec import load_problem, load_problem_text
from mechgrade.spec.dynamics import Integration, WorkEnergy, instant_of_objective

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = shipped_dir("problems")


def alone(problem, variants):
    out = []
    for givens in variants:
        try:
            out.append(solve(problem, givens=givens))
        except MechgradeError as err:
            out.append(err)
    return out


def together_and_alone(problem, variants):
    """The ``variants`` solved together, none of them left to be solved alone, and each
    solved alone."""
    template = _template(problem)
    assert template is not None
    assert all(s is not None for s in template.solve(variants))  # none went alone
    return solve_variants(problem, variants), alone(problem, variants)


EXACT = (1e-8, 1e-10)
"""Batched and alone agree to this (relative, absolute) where both take the same steps."""

INTEGRATED = (1e-6, 1e-9)
"""...and to this after an integration to an event, the specification's bound (far inside the
checks' 1e-5). Since one integrator steps a column alone or among others, in the same
arithmetic (numpy's powers for numbers and arrays alike, the stages padded for BLAS), the
integrated variants of the library come out the same bits both ways."""


def close(a, b, tolerance=EXACT) -> bool:
    if a is None or b is None:
        return a is b
    rtol, atol = tolerance
    return bool(np.allclose(np.atleast_1d(a), np.atleast_1d(b), rtol=rtol, atol=atol))


def assert_same(together, one, tolerance=EXACT, generated=True):
    if isinstance(one, MechgradeError):
        assert type(together) is type(one) and str(together) == str(one)
        return
    assert [r.id for r in together.results] == [r.id for r in one.results]
    for a, b in zip(together.results, one.results):
        assert (a.expr, a.symbols, a.unit, a.plausible) == (b.expr, b.symbols, b.unit, b.plausible)
        assert close(a.value, b.value, tolerance), a.id
        assert [(m.message, m.credit) for m in a.mistakes] == \
            [(m.message, m.credit) for m in b.mistakes]
        assert all(close(x.value, y.value, tolerance) for x, y in zip(a.mistakes, b.mistakes))
        if not generated:  # worked out by the same code from what is compared here
            continue
        if tolerance == EXACT:
            assert [(m.code, m.message, m.expr) for m in a.generated_mistakes] == \
                [(m.code, m.message, m.expr) for m in b.generated_mistakes], a.id
            assert all(close(x.value, y.value) for x, y in
                       zip(a.generated_mistakes, b.generated_mistakes)), a.id
        else:
            assert_same_mistakes(a, b, tolerance)
    assert [f.id for f in together.failures] == [f.id for f in one.failures]
    assert [str(f.error) for f in together.failures] == [str(f.error) for f in one.failures]
    assert [w.message for w in together.warnings] == [w.message for w in one.warnings]
    assert together.dof == one.dof
    assert [(s.name, s.unit, s.given) for s in together.state] == \
        [(s.name, s.unit, s.given) for s in one.state]
    assert close([s.si for s in together.state], [s.si for s in one.state], tolerance)


def assert_same_mistakes(a, b, tolerance):
    """The generated mistakes of two answers that agree to ``tolerance``: the same mistakes
    with the same values, but for one that only one side keeps because, within that
    tolerance, it equals the answer or another mistake, or is a zero (kept mistakes differ
    from those by 1e-9 relative: a borderline case either side may fall on)."""
    mine = {(m.code, m.message, m.expr): m.value for m in a.generated_mistakes}
    theirs = {(m.code, m.message, m.expr): m.value for m in b.generated_mistakes}
    for key in mine.keys() & theirs.keys():
        assert close(mine[key], theirs[key], tolerance), (a.id, key)
    values = [a.value, b.value, *mine.values(), *theirs.values()]
    for key in mine.keys() ^ theirs.keys():
        value = mine.get(key, theirs.get(key))
        others = [v for v in values if v is not value]
        assert close(value, 0.0 * np.atleast_1d(value), tolerance) or any(
            close(value, v, tolerance) for v in others), (a.id, key)


def scaled(problem, keys, count=6):
    """Variants that scale the givens ``keys`` by 0.8 to 1.2."""
    si = {k: g.si for g in problem.givens for k in keys if str(g.key.text).strip() == k}
    return [{k: v * (0.8 + 0.4 * ((3 * n + i) % 7) / 6) for i, (k, v) in enumerate(si.items())}
            for n in range(count)]


@pytest.mark.parametrize("name, keys", [
    ("bowling_3_15_4_pendulum", ["L", "theta'"]),        # linear levels
    ("ruina_10_2_limacon", ["b", "theta'"]),                  # a non-linear level from guesses
    ("bowling_3_15_6_gears", ["teeth_A", "dot(angacc(B, N), N.z)"]),  # free unknowns
    ("pendulum_pin_reaction", ["L", "m"]),               # dynamics at an instant
    ("rod_strikes_ledge", ["L", "v0", "e"]),             # an impact
])
def test_variants_solved_together_are_the_variants_solved_alone(name, keys):
    problem = load_problem(PROBLEMS / f"{name}.yaml")
    variants = scaled(problem, keys)
    assert variants and variants[0]
    assert _template(problem) is not None
    for together, one in zip(solve_variants(problem, variants), alone(problem, variants)):
        assert_same(together, one)


def misread_alone(monkeypatch) -> list[dict]:
    """The givens of each misread instant solved alone from now on (one solve's way)."""
    from mechgrade.solve import mutants

    again: list[dict] = []
    real = mutants.solve_numeric_columns

    def counted(problem, p, givens, only):
        again.extend(givens)
        return real(problem, p, givens, only)

    monkeypatch.setattr(mutants, "solve_numeric_columns", counted)
    return again


@pytest.mark.slow  # a slow end-to-end check (a cold derivation, over 1 s)
def test_misread_givens_without_a_solution_name_no_mistake_together_as_alone():
    # w' read in m/s: 48 to 72 m/s, against an airspeed of 66.67 m/s. The misreadings
    # batch does not confirm are solved together (solve_numeric_columns), as given_mistakes
    # solves those of one student
    problem = load_problem(PROBLEMS / "airplane_crosswind_heading.yaml")
    variants = scaled(problem, ["w'"], count=7)
    together = solve_variants(problem, variants)
    for a, one in zip(together, alone(problem, variants)):
        assert_same(a, one)
    named = [any(m.code == "given_unit" and "w' =" in m.message
                 for m in s.result("heading").generated_mistakes) for s in together]
    assert named == [v["w'"] * 3.6 < 240 / 3.6 for v in variants]  # the number, in m/s
    assert any(named) and not all(named)


def test_misread_givens_that_break_the_positions_they_fix_are_refused_together_as_alone(
        monkeypatch):
    # x, y and alpha fix the linkage, so an angle or length misread breaks its loop: one solve
    # refuses that instant (the givens conflict), and the class refuses it by the same rule
    # instead of solving it again alone
    problem = load_problem(PROBLEMS / "bowling_3_15_8_connected_blocks.yaml")
    variants = scaled(problem, ["y'"])
    one_by_one = alone(problem, variants)
    solve_variants(problem, scaled(problem, ["y'"], count=1))  # the class's template built
    again = misread_alone(monkeypatch)
    together = solve_variants(problem, variants)
    assert again == []
    for a, one in zip(together, one_by_one):
        assert_same(a, one)
    assert any(m.code == "given_sign" for m in together[0].result("xdot").generated_mistakes)


def test_variants_asking_for_the_first_positive_root_are_solved_together_as_alone(monkeypatch):
    # y = 3 m is passed twice (up, then down): the first positive root is the earlier one,
    # which the reference's root (the landing, 2.04 s) does not continue to; y = -3 m has
    # one positive root and one negative. A misread given with no positive root (beta read
    # as radians, -0.57 rad) is refused together, as one solve refuses it
    from mechgrade.solve import batch

    problem = load_problem(ROOT / "tests" / "data" / "authoring_mistakes"
                           / "solve_t_first_positive.yaml")
    variants = [{"y": 3.0}, {"y": -3.0}, {"v0": 25.0, "beta": np.radians(33.0)}]
    left: list[int] = []  # the columns answered alone inside the class

    def spied(problem, reach, maps, chosen, overrides, columns, which):
        left.extend(which)
        return answer_alone(problem, reach, maps, chosen, overrides, columns, which)

    monkeypatch.setattr(batch, "answer_alone", spied)
    _solved_together(problem, [{"y": 1.0}])  # the class's template built
    again = misread_alone(monkeypatch)
    solved = _solved_together(problem, variants)
    assert [together for _, together in solved] == [True, True, True] and left == []
    assert again == []
    for (a, _), b in zip(solved, alone(problem, variants)):
        assert_same(a, b)
    t = next(s.si for s in solved[0][0].state if s.name == "t")
    assert t == pytest.approx((20 * 0.5 - (20**2 * 0.25 - 2 * 9.81 * 3) ** 0.5) / 9.81)


@pytest.mark.slow  # a slow end-to-end check (over 5 s)
def test_a_problem_with_symbolic_objectives_only_is_solved_together():
    problem = load_problem(PROBLEMS / "ruina_sec10_bug_on_tire.yaml")
    assert _template(problem) is not None
    together, = solve_variants(problem, [{}])
    assert_same(together, solve(problem))


def test_drawn_variants_solved_together_are_the_drawn_variants_solved_alone():
    problem = load_problem(shipped_dir("examples") / "hw2_variants" / "pendulum_variants.yaml")
    variants = [dict(draw_variant(problem, "s", str(n)).overrides) for n in range(12)]
    for together, one in zip(solve_variants(problem, variants), alone(problem, variants)):
        assert_same(together, one)


def test_a_degenerate_variant_warns_as_when_solved_alone():
    problem = load_problem(ROOT / "tests" / "data" / "variants" / "degenerate_range.yaml")
    variants = [{"theta": np.pi / 2}, {"theta": np.pi / 6, "a": 0.25}]
    together = solve_variants(problem, variants)
    assert any("degenerate configuration" in w.message for w in together[0].warnings)
    for a, b in zip(together, alone(problem, variants)):
        assert_same(a, b)


def test_only_the_variant_that_fails_a_screen_together_is_answered_by_the_one_column_step(
        monkeypatch):
    from mechgrade.solve import batch

    problem = load_problem(ROOT / "tests" / "data" / "variants" / "degenerate_range.yaml")
    variants = [{"theta": np.pi / 6}, {"theta": np.pi / 2}, {"theta": np.pi / 6, "a": 0.25}]
    left: list[list[int]] = []  # the columns each group answers alone

    def spied(problem, reach, maps, chosen, overrides, columns, which):
        left.append(list(which))
        return answer_alone(problem, reach, maps, chosen, overrides, columns, which)

    monkeypatch.setattr(batch, "answer_alone", spied)
    solved = _solved_together(problem, variants)
    # the degenerate one (the collar on the pivot) inside the loop, none by solve()
    assert [together for _, together in solved] == [True, True, True]
    assert [w for w in left if w] == [[1]]
    for (a, _), b in zip(solved, alone(problem, variants)):
        assert_same(a, b)


def test_a_variant_with_givens_the_reference_lacks_or_removes_is_solved_alone():
    problem = load_problem(PROBLEMS / "bowling_3_15_4_pendulum.yaml")
    variants = [{"theta'": None}, {"L": 0.7, "no_such_given": 1.0}, {"L": 0.7}]
    together = solve_variants(problem, variants)
    for a, b in zip(together, alone(problem, variants)):
        assert_same(a, b)


def test_a_variant_whose_givens_conflict_fails_as_when_solved_alone():
    problem = load_problem(PROBLEMS / "bowling_3_15_8_connected_blocks.yaml")
    variants = [{"L": 0.2}]  # the rod no longer fits the positions given: they conflict
    together, = solve_variants(problem, variants)
    one, = alone(problem, variants)
    assert together.failures and "conflict" in str(together.failures[0].error)
    assert [str(f.error) for f in together.failures] == [str(f.error) for f in one.failures]
    assert_same(together, one)


# ---------------------------------------------------------------------------- analyses


ASKED_BEFORE_THE_EVENT = ("ball_thrown_with_drag_apex_and_landing", "damped_block_positions",
                    "three_cart_chain_vibration")
"""Integrated problems with objectives asked before the event (an objective's own time,
coordinate or rate): the integrator over columns stops each variant at that instant too."""
IN_PHASES = ("bowling_ball_skids_then_rolls",)
"""Integrated problems whose motion goes on in another phase once a slip ends, with
objectives asked 'when' an equation holds: each variant switches phase at its own instant."""


def _reached_otherwise(path: Path) -> bool:
    """Whether the spec's instant is reached by work-energy, by integrating the motion or
    with a design parameter solved for (read from the text, so collecting stays fast)."""
    return path.stem not in ASKED_BEFORE_THE_EVENT + IN_PHASES and \
        bool(re.search(r"^\s+(work_energy|integrate|design):", path.read_text(), re.M))


REACHED_OTHERWISE = [path for path in sorted(PROBLEMS.glob("*.yaml"))
                     + sorted(shipped_dir("examples").glob("*/*.yaml"))
                     if _reached_otherwise(path)]


def with_drawn_parameters(path: Path, folder: Path):
    """The problem at ``path`` with a ``variants:`` section drawing every parameter it gives
    (a plain number) between 0.8 and 1.2 times its value; a problem that has one keeps it."""
    problem = load_problem(path)
    if problem.variants is not None:
        return problem
    parameters = {q.name for q in problem.parameters}
    lines = [f"    {to_text(g.key.node)}: {{from: {min(0.8 * g.value, 1.2 * g.value)!r}, "
             f"to: {max(0.8 * g.value, 1.2 * g.value)!r}, sig_figs: 4}}"
             for g in problem.givens if isinstance(g.key.node, Name)
             and g.key.node.id in parameters and g.value_expr is None and g.value]
    text = path.read_text()
    for line in problem.statement.splitlines():  # each drawn value a placeholder, as an
        shown = line                               # author writes it
        for g in problem.givens:
            if any(f"    {to_text(g.key.node)}:" in drawn for drawn in lines):
                shown = re.sub(rf"(?<![\w.]){re.escape(g.text)}(?!\w)",
                               f"{{{to_text(g.key.node)}}}", shown)
        text = text.replace(f"  {line}\n", f"  {shown}\n")
    copy = folder / path.name
    copy.write_text(text + "\nvariants:\n  draw:\n" + "\n".join(lines) + "\n")
    return load_problem(copy)


REACHED_IN_THE_FAST_CORE = frozenset({
    "pendulum_release",  # work-energy
    "boat_coasting_quadratic_drag",  # integrate to an event
    "gyroscope_pivot_precession"})  # design
"""One of each way of reaching the instant; `pytest -m slow` checks every other one
(the parity of 26 problems took about a minute of the default command's CPU)."""


@pytest.mark.parametrize("path", [
    path if path.stem in REACHED_IN_THE_FAST_CORE else pytest.param(path, marks=pytest.mark.slow)
    for path in REACHED_OTHERWISE], ids=lambda path: path.stem)
def test_variants_reached_by_energy_integration_or_design_solved_together_are_those_alone(
        path, tmp_path):
    problem = with_drawn_parameters(path, tmp_path)
    dynamics = problem.dynamics
    assert isinstance(dynamics.analysis, (WorkEnergy, Integration)) or dynamics.design
    variants = [dict(draw_variant(problem, "batch", str(n)).overrides) for n in range(3)]
    assert all(variants)
    template = _template(problem)
    assert template is not None
    assert all(s is not None for s in template.solve(variants))  # none went alone
    tolerance = INTEGRATED if isinstance(dynamics.analysis, Integration) else EXACT
    pairs = zip(solve_variants(problem, variants), alone(problem, variants))
    for k, (together, one) in enumerate(pairs):
        # the generated mistakes of a dynamics solution are solved alone from its givens,
        # answers and state (slow after an integration): those of one variant are compared
        assert_same(together, one, tolerance, generated=k == 0)


@pytest.mark.parametrize("name", ASKED_BEFORE_THE_EVENT)
def test_variants_asked_before_the_event_are_reached_together_there_as_alone(name, tmp_path):
    problem = with_drawn_parameters(PROBLEMS / f"{name}.yaml", tmp_path)
    template = _template(problem)
    assert template is not None and any(instant_of_objective(problem, group.overrides)
                                        is not None for group in template.groups)
    variants = [dict(draw_variant(problem, "batch", str(n)).overrides) for n in range(2)]
    assert all(s is not None for s in template.solve(variants))  # no variant alone whole
    for together, one in zip(solve_variants(problem, variants), alone(problem, variants)):
        assert_same(together, one, EXACT, generated=False)



@pytest.mark.slow  # a slow end-to-end check (a cold derivation of both phases, over 2 s)
@pytest.mark.parametrize("name", IN_PHASES)
def test_variants_of_a_motion_in_phases_are_reached_together_as_alone(name, tmp_path):
    problem = with_drawn_parameters(PROBLEMS / f"{name}.yaml", tmp_path)
    template = _template(problem)
    assert template is not None
    variants = [dict(draw_variant(problem, "batch", str(n)).overrides) for n in range(3)]
    assert all(s is not None for s in template.solve(variants))  # none went alone
    for k, (together, one) in enumerate(zip(solve_variants(problem, variants),
                                            alone(problem, variants))):
        assert_same(together, one, EXACT, generated=k == 0)


@pytest.mark.slow  # a slow end-to-end check (a cold derivation, over 2 s)
def test_variants_asked_when_on_a_motion_without_phases_are_reached_together_as_alone():
    throw = (PROBLEMS / "ball_thrown_with_drag_apex_and_landing.yaml").read_text()
    problem = load_problem_text(throw.replace(
        "    givens: {y': 0 m/s}\n    expect: {value: 9.940268}",
        "    when: y' = 0\n    expect: {value: 9.940268}"), "p.yaml")
    variants = [{"m": 30.0}, {"m": 35.0}]
    template = _template(problem)
    assert template is not None
    assert all(s is not None for s in template.solve(variants, ["apex_height"]))
    for together, one in zip(solve_variants(problem, variants), alone(problem, variants)):
        assert_same(together, one, EXACT, generated=False)


@pytest.mark.slow  # a slow end-to-end check (a cold derivation of both phases, over 2 s)
def test_a_variant_whose_grip_fails_or_whose_motion_ends_first_fails_in_the_class_as_alone():
    problem = load_problem(PROBLEMS / "bowling_ball_skids_then_rolls.yaml")
    # the grip needs more than mu_s N; the ball stops before it rolls and before 2 s
    variants = [{"mu_s": 0.04}, {"v0": 2.0}, {"v0": 6.0}]
    said = ["grip then needs more friction than mu_s N", "does not hold before the event", None]
    for a, b, words in zip(*together_and_alone(problem, variants), said):
        assert words in str(b.failures[0].error) if words else not b.failures
        assert_same(a, b, EXACT, generated=False)


@pytest.mark.slow  # a slow end-to-end check (a cold derivation, over 1 s)
def test_a_variant_whose_slip_ends_before_its_instant_asked_when_is_solved_alone(monkeypatch):
    problem = load_problem(ROOT / "tests/data/phases/ball_slides_on_past_its_slip.yaml")
    variants = [{"mu_k": 0.01}, {"mu_k": 0.12}]  # slides on to 60 radii; stops slipping first
    import mechgrade.solve.batch as batch

    left: list[list[int]] = []

    def spied(problem, reach, maps, chosen, overrides, columns, which):
        left.append(list(which))
        return answer_alone(problem, reach, maps, chosen, overrides, columns, which)

    monkeypatch.setattr(batch, "answer_alone", spied)
    assert _template(problem) is not None
    together = solve_variants(problem, variants, ["v_rolls"])
    assert [w for w in left if w] == [[1]]  # that column only, inside the loop
    assert_same(together[0], solve(problem, givens=variants[0], objectives=["v_rolls"]), EXACT,
                generated=False)
    assert "the integration stalls near t = 1.41987 s" in str(together[1])


REACHED_OTHERWISE_COUNT = 27  # 26 problems (two gyroscopes by design) and examples/hw3's pendulum


ASKED_AT_A_SPEED = """  - id: drop_at_speed
    prompt: How far the collar has dropped when its speed is 3 sqrt(g d) / 4.
    find: -y
    when: speed(C, N) = 3*sqrt(g*d)/4
    kind: scalar
    unit: m
  - id: spring_energy_at_speed
    prompt: The energy in the spring then.
    find: pe(spring)
    when: speed(C, N) = 3*sqrt(g*d)/4
    kind: scalar
    unit: J
"""


def test_variants_asked_when_are_walked_together_and_one_that_never_gets_there_fails_as_alone():
    # a stiffer spring stops the collar before it is that fast (k = 300 N/m: it turns back
    # at y = -0.36 m): those objectives fail with the range searched, the others are answered
    problem = load_problem_text((PROBLEMS / "collar_spring_vertical_rod.yaml").read_text()
                                + ASKED_AT_A_SPEED, "p.yaml")
    variants = [{"k": 150.0}, {"k": 300.0}, {"k": 250.0}, {"k": 350.0}]
    template = _template(problem)
    assert template is not None
    assert all(s is not None for s in template.solve(variants))  # none went alone
    together = solve_variants(problem, variants)
    assert [sorted(f.id for f in s.failures) for s in together] == \
        [[], ["drop_at_speed", "spring_energy_at_speed"], [], ["drop_at_speed",
                                                               "spring_energy_at_speed"]]
    assert "where the motion turns back" in str(together[1].failures[0].error)
    for mine, one in zip(together, alone(problem, variants)):
        assert_same(mine, one, EXACT, generated=False)
        assert [(f.id, str(f.error)) for f in mine.failures] == \
            [(f.id, str(f.error)) for f in one.failures]
        assert mine.state == one.state


def test_every_shipped_problem_reached_otherwise_is_covered():
    assert len(REACHED_OTHERWISE) == REACHED_OTHERWISE_COUNT


@pytest.mark.parametrize("variants, said", [
    ([{"mu": 0.0}, {"mu": 0.25}], "does not happen within 60 s"),  # no friction: slides on
    ([{"v0": 1e-13}, {"v0": 5.0}], "slip velocity is zero"),  # stops at once: no slip left
], ids=["event-never-happens", "no-slip-just-before-the-event"])
def test_a_variant_that_fails_on_the_way_to_its_event_fails_in_the_class_as_alone(variants,
                                                                                  said):
    problem = load_problem(PROBLEMS / "block_slides_on_cart.yaml")
    template = _template(problem)
    assert template is not None
    assert all(s is not None for s in template.solve(variants))  # neither went alone
    together = solve_variants(problem, variants)
    one = alone(problem, variants)
    assert one[0].failures and all(said in str(f.error) for f in one[0].failures)
    for a, b in zip(together, one):
        assert_same(a, b, INTEGRATED, generated=False)


@pytest.mark.slow  # a slow end-to-end check (a cold derivation, over 2 s)
def test_a_variant_whose_event_comes_before_its_instant_fails_in_the_class_as_alone():
    problem = load_problem(PROBLEMS / "three_cart_chain_vibration.yaml")
    variants = [{"T": 0.2}, {"T": 1.4}]  # the record ends before, after 250 ms
    together = solve_variants(problem, variants)
    one = alone(problem, variants)
    failed = {f.id: str(f.error) for f in one[0].failures}
    assert "does not hold before the event" in failed["x1_at_250ms"]
    assert not one[1].failures
    for a, b in zip(together, one):
        assert_same(a, b, EXACT, generated=False)


@pytest.mark.slow  # a slow end-to-end check (a cold derivation, over 2 s)
def test_a_variant_at_rest_in_an_objectives_own_rate_waits_for_its_next_crossing_in_the_class():
    problem = load_problem(PROBLEMS / "three_cart_chain_vibration.yaml")
    variants = [{"v0": 0.0}, {"v0": 0.3}]  # at rest, x3' = 0 holds at the start and stays
    together, one = together_and_alone(problem, variants)
    failed = {f.id: str(f.error) for f in one[0].failures}
    assert "'x3': 0 m/s' holds at the start (t = 0) and stays so" in failed["time_cart3_stops"]
    for a, b in zip(together, one):
        assert_same(a, b, EXACT, generated=False)


def test_a_class_reaches_an_own_instant_that_holds_at_the_start_at_its_next_crossing(
        monkeypatch):
    # x = 0 mm holds at the start: the block's return, as alone; at rest it stays there,
    # refused together at its given as alone (the event, x = a, is not at the start)
    from mechgrade.solve import batch

    swing = (PROBLEMS / "damped_block_positions.yaml").read_text()
    problem = load_problem_text(swing.replace("until: x = 0 ", "until: x = a ")
                                .replace("givens: {x: 20 mm}", "givens: {x: 0 mm}", 1), "p.yaml")
    variants = [{"v0": 1.0}, {"v0": 0.25}, {"v0": 0.0}]
    left: list[int] = []  # the columns answered alone inside the class

    def spied(problem, reach, maps, chosen, overrides, columns, which):
        left.extend(which)
        return answer_alone(problem, reach, maps, chosen, overrides, columns, which)

    monkeypatch.setattr(batch, "answer_alone", spied)
    together, one = together_and_alone(problem, variants)
    assert left == []
    assert together[0].result("time_to_20mm").value > 0
    failed = {f.id: str(f.error) for f in together[2].failures}
    assert failed["time_to_20mm"] == (
        "p.yaml:61:17: objectives[2].givens.x: 'x: 0 mm' holds at the start (t = 0) and stays "
        "so: expected a motion that leaves it")
    for a, b in zip(together, one):
        assert_same(a, b, EXACT, generated=False)


@pytest.mark.slow  # a slow end-to-end check (over 5 s)
def test_a_variant_that_cannot_reach_its_instant_fails_as_when_solved_alone():
    problem = load_problem(PROBLEMS / "ruina_9_19_falling_ladder.yaml")
    variants = [{"theta0": np.radians(50)}, {"theta0": np.radians(75)}]  # below theta: no energy
    together = solve_variants(problem, variants)
    one = alone(problem, variants)
    assert isinstance(one[0], MechgradeError) or one[0].failures
    for a, b in zip(together, one):
        assert_same(a, b)


@pytest.mark.slow  # a slow end-to-end check (a cold derivation, over 1 s)
def test_a_variant_whose_friction_slips_fails_in_the_batch_as_when_solved_alone():
    problem = load_problem(PROBLEMS / "block_on_turntable.yaml")
    variants = [{"mu_s": 0.3}, {"mu_s": 0.7}]  # sticking needs mu >= 0.4931
    template = _template(problem)
    assert template is not None
    assert all(s is not None for s in template.solve(variants))  # not re-solved alone
    together = solve_variants(problem, variants)
    one = alone(problem, variants)
    assert "slips at P" in str(one[0].failures[0].error)
    assert [r.id for r in one[0].results] == ["mu_needed_symbolic"]
    for a, b in zip(together, one):
        assert_same(a, b)


@pytest.mark.slow  # a slow end-to-end check (over 5 s: omega_n's derivation)
def test_a_variant_off_its_equilibrium_fails_in_the_batch_as_when_solved_alone():
    problem = load_problem(PROBLEMS / "block_on_spring_us_units.yaml")
    variants = [{"W": 50.0}, {"k": 4000.0, "y": 0.2}]  # y is no longer W/k below the spring
    template = _template(problem)
    assert template is not None
    assert all(s is not None for s in template.solve(variants))  # not re-solved alone
    together = solve_variants(problem, variants)
    one = alone(problem, variants)
    assert all(isinstance(o, MechgradeError) and "not an equilibrium" in str(o) for o in one)
    for a, b in zip(together, one):
        assert_same(a, b)


@pytest.mark.slow  # a slow end-to-end check (a cold derivation, over 1 s)
def test_a_variant_whose_slip_ends_and_sticks_before_its_event_fails_in_the_batch_as_alone():
    problem = load_problem(PROBLEMS / "crate_pushed_impulse_momentum.yaml")
    # a push too weak to keep the crate sliding: it stops at t = 2 m/s / 1.511 m/s^2
    variants = [{"F": 100.0}, {"F": 300.0}]
    template = _template(problem)
    assert template is not None
    assert all(s is not None for s in template.solve(variants))  # not re-solved alone
    together = solve_variants(problem, variants)
    one = alone(problem, variants)
    assert isinstance(one[0], MechgradeError)
    assert "slip ends at t = 1.32" in str(one[0]) and "sticks" in str(one[0])
    for a, b in zip(together, one):
        assert_same(a, b, INTEGRATED, generated=False)


@pytest.mark.slow  # derives the problem and its mistaken copy (3 s)
def test_each_variant_gets_its_own_mistaken_constraint_as_solve_gives_it():
    problem = load_problem(shipped_dir("problems") / "truck_hoists_crate_pulley.yaml")
    together = solve_variants(problem, [{"x": 4.0}, {"x": 3.0}])
    for outcome, x in zip(together, (4.0, 3.0)):
        alone = solve(problem, givens={"x": x}).result("velocity").generated_mistakes
        mine = outcome.result("velocity").generated_mistakes
        assert [(m.code, m.value) for m in mine if m.code == "strands_miscounted"] == [
            (m.code, pytest.approx(m.value)) for m in alone if m.code == "strands_miscounted"]
        assert len([m for m in mine if m.code == "strands_miscounted"]) == 1


@pytest.mark.slow  # derives the problem and its mistaken copy (3 s)
def test_a_mistaken_constraint_is_solved_over_the_class_by_its_own_template(monkeypatch):
    # the mistaken model's reference is degenerate (O and B coincide): no reason to solve
    # its instants one by one, whose values alone are read
    problem = load_problem(shipped_dir("problems") / "truck_hoists_crate_pulley.yaml")
    variants = [{"x": x} for x in (4.0, 3.0, 3.5)]
    alone = [solve(problem, givens=g).result("velocity").generated_mistakes for g in variants]
    import mechgrade.solve.batch as batch

    def refused(*args, **kwargs):
        raise AssertionError("a mistaken model's instant solved alone")

    monkeypatch.setattr(batch, "values_alone", refused)
    for outcome, mistakes in zip(solve_variants(problem, variants), alone):
        mine = [(m.code, m.value) for m in outcome.result("velocity").generated_mistakes
                if m.code == "strands_miscounted"]
        assert mine == [(m.code, pytest.approx(m.value, rel=1e-9)) for m in mistakes
                        if m.code == "strands_miscounted"]
        assert len(mine) == 1


MID_STROKE = """  - id: speed_mid
    prompt: The speed halfway through the stroke.
    find: phi'
    givens: {t: 0.1 s}
    kind: scalar
    unit: rpm
"""


def test_a_design_asked_at_an_objectives_own_instant_is_read_there_in_a_class_as_alone():
    # the design (R) holds at the end of the stroke, t = T; speed_mid is asked at t = 0.1 s,
    # where one solve reads it with the variant's R (the speed drops linearly: 285 rpm when
    # T = 0.2 s); a class read it at the end of the stroke (270 rpm)
    text = (PROBLEMS / "flywheel_speed_drop.yaml").read_text()
    problem = load_problem_text(text.replace("tags:", MID_STROKE + "tags:"), "flywheel.yaml")
    variants = [{"M": 1400.0}, {"M": 1600.0, "T": 0.4}]
    together, one = together_and_alone(problem, variants)
    for a, b in zip(together, one):
        assert_same(a, b, INTEGRATED, generated=False)
    assert [s.result("speed_mid").value for s in together] == pytest.approx([285.0, 292.5])


HALF_DROP = """  - id: t_half_drop
    prompt: The moment the speed has dropped by 5 %.
    find: t
    when: phi' = 0.95*w0
    kind: scalar
    unit: s
"""


def test_a_design_asked_when_is_solved_together_as_alone():
    # each variant's R solved at the end of the stroke first, then its motion integrated to
    # where the speed has dropped by 5 % (half the stroke: the drop is linear); without a
    # punch (M = 0) no R makes the speed drop, refused as alone
    text = (PROBLEMS / "flywheel_speed_drop.yaml").read_text()
    problem = load_problem_text(text.replace("tags:", HALF_DROP + "tags:"), "flywheel.yaml")
    variants = [{"M": 1400.0}, {"M": 1500.0, "T": 0.3}, {"M": 0.0}]
    together, one = together_and_alone(problem, variants)
    for a, b in zip(together, one):
        assert_same(a, b, INTEGRATED, generated=False)
    assert [s.result("t_half_drop").value for s in together[:2]] == pytest.approx([0.1, 0.15])
    assert "design: no value of R" in str(together[2])


def test_a_design_that_converges_for_no_value_is_refused_in_a_class_as_alone():
    # down a 10 deg incline the wheel's centre stays below 0.2 g for every R: the design stage
    # over the class does not converge for that variant, whose objectives at the instant fail
    # with the located error they get alone
    path = PROBLEMS / "ruina_9_21_wheel_incline.yaml"
    problem = load_problem(path)
    variants = [{"theta": np.radians(30.0)}, {"theta": np.radians(10.0)}]
    (fine, refused), (fine_alone, refused_alone) = solve_variants(problem, variants), \
        alone(problem, variants)
    assert fine.result("R_min").value == pytest.approx(fine_alone.result("R_min").value,
                                                       rel=1e-9)
    with pytest.raises(MechgradeError) as together:
        refused.result("R_min")
    with pytest.raises(MechgradeError) as one:
        refused_alone.result("R_min")
    assert str(together.value) == str(one.value)
    assert str(one.value).startswith(f"{path}:") and \
        "design: no value of R near 0.15 (SI)" in str(one.value)


def test_a_class_is_solved_with_the_garbage_collector_paused_and_leaves_it_on(monkeypatch):
    import gc

    from mechgrade.solve import batch

    problem = load_problem(PROBLEMS / "bowling_3_15_4_pendulum.yaml")
    template = type(_template(problem))
    solve_class, running = template.solve, []

    def watched(self, *args, **kwargs):
        running.append(gc.isenabled())
        return solve_class(self, *args, **kwargs)

    monkeypatch.setattr(template, "solve", watched)
    solved = batch.solve_variants(problem, [{"L": 0.6 + i / 1000} for i in range(30)])
    assert len(solved) == 30 and all(isinstance(s, Solution) for s in solved)
    assert running == [False]
    assert gc.isenabled()


def test_a_class_reads_the_balances_once_per_phase_for_all_its_integrated_groups(monkeypatch):
    # damped_block_positions asks five instants (t = 30 ms, x = 20 mm, x' = 0, the event and
    # the event with c = 20): one pass reaches them all, and the balances at the instants
    # are solved once for the own instants and once for the events, not once per group
    from mechgrade.solve import batch

    problem = load_problem(PROBLEMS / "damped_block_positions.yaml")
    variants = [{"m": 1.2}, {"m": 0.9}, {"c": 5.0}]
    read = []
    checked = batch.checked
    monkeypatch.setattr(batch, "checked", lambda at, kp: read.append(at) or checked(at, kp))
    together = solve_variants(problem, variants)
    assert len(read) == 2
    monkeypatch.setattr(batch, "checked", checked)
    for a, b in zip(together, alone(problem, variants)):
        assert_same(a, b, INTEGRATED, generated=False)
