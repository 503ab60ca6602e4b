"""A dynamics problem's solutions kept in the disk cache: for any givens and objectives, each
variant solved together, the error solving raised; read back exactly as solved, without
solving again; a spoilt entry solved and written again; a second grading run derives nothing."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

import mechgrade.solve.batch as batch
import mechgrade.solve.entry as entry
import mechgrade.solve.stored as stored
from mechgrade.errors import MechgradeError, SolveError
from mechgrade.expressions.syntax import to_text
from mechgrade.solve import solve
from mechgrade.solve.batch import solve_variants
from mechgrade.spec import load_problem

ROOT = Path(__file__).resolve().parents[2]
# integrates to an event, and its derivation and generated mistakes are quick to derive
COASTING = ROOT / "problems" / "boat_coasting_quadratic_drag.yaml"
ATWOOD = ROOT / "problems" / "atwood_machine.yaml"
HW3 = ROOT / "examples" / "hw3_dynamics"
PENDULUM_ONLY = ROOT / "tests" / "data" / "cache" / "assignment.yaml"  # hw3's, with its answers


def overrides(problem, *scales: float) -> list[dict[str, float]]:
    """Givens overrides: the problem's first given scaled by each of ``scales``."""
    given = problem.givens[0]
    return [{to_text(given.key.node): given.si * scale} for scale in scales]


def not_solved(*args, **kwargs):
    raise AssertionError("solved again: expected to be read from the cache")


@pytest.mark.parametrize("givens, objectives", [
    ("scaled", None), (None, ["a1"]), ("scaled", ["tension", "a1"])],
    ids=["givens", "objectives", "both"])
def test_a_dynamics_solution_for_other_givens_and_objectives_is_read_back_as_solved(
        givens, objectives, disk, forget, monkeypatch):
    problem = load_problem(ATWOOD)
    given = overrides(problem, 1.3)[0] if givens else None
    solved = solve(problem, givens=given, objectives=objectives)
    assert any(r.generated_mistakes for r in solved.results)
    forget()
    monkeypatch.setattr(entry, "_solve_dynamics", not_solved)
    again = solve(problem, givens=given, objectives=objectives)
    assert stored.same(again, solved)
    assert [r.generated_mistakes for r in again.results] == \
        [tuple(r.generated_mistakes) for r in solved.results]


def test_each_givens_and_objectives_has_an_entry_of_its_own(disk):
    problem = load_problem(ATWOOD)
    a, b = overrides(problem, 1.2, 1.4)
    keys = {stored.solution_key(problem, g, o) for g in (None, a, b) for o in (None, ["a1"])}
    assert None not in keys and len(keys) == 6
    assert stored.solution_key(problem, a, ["tension", "a1"]) == \
        stored.solution_key(problem, {k: float(v) for k, v in a.items()}, ("a1", "tension"))
    solve(problem, givens=a, objectives=["a1"])
    names = {p.name for p in (disk / "entries").iterdir()}
    assert stored.solution_key(problem, a, ["a1"]) + ".json" in names
    assert stored.solution_key(problem, b, ["a1"]) + ".json" not in names


def test_the_error_solving_raised_is_kept_and_raised_again(disk, forget, monkeypatch):
    problem = load_problem(ATWOOD)
    with pytest.raises(SolveError) as first:
        solve(problem, objectives=["no_such_objective"])
    forget()
    monkeypatch.setattr(entry, "_solve_dynamics", not_solved)
    with pytest.raises(SolveError) as again:
        solve(problem, objectives=["no_such_objective"])
    assert str(again.value) == str(first.value)


def test_an_error_its_entry_cannot_say_whole_is_not_kept(disk):
    class Odd(SolveError):
        pass

    key = "e" * 64
    stored.store_outcome(key, Odd("no"))  # not an error mechgrade names
    stored.store_outcome(key, SolveError("no"))
    assert isinstance(stored.load_outcome(key), SolveError)
    assert not isinstance(stored.load_outcome(key), Odd)


NOWHERE = {"file": None, "line": None, "column": None, "field": None}


@pytest.mark.parametrize("spoil", [
    lambda data: {**data, "dof": "many"},
    lambda data: {"error": "SystemExit", "message": "no", "where": NOWHERE},
    lambda data: {**data, "failures": [{"id": "x", "error": {
        "error": "SystemExit", "message": "no", "where": NOWHERE}}]},
    lambda data: [],
], ids=["layout", "foreign-error", "foreign-failure", "not-an-outcome"])
def test_a_spoilt_solution_entry_is_solved_and_written_again(spoil, disk, forget, entry_file,
                                                             rewrite_entry):
    # signed with the folder's key: read as far as the codec, which refuses it
    problem = load_problem(COASTING)
    given = overrides(problem, 1.1)[0]
    right = solve(problem, givens=given)
    path = entry_file(stored.solution_key(problem, given, None))
    rewrite_entry(path, spoil, signed=True)
    forget()
    assert stored.same(solve(problem, givens=given), right)
    assert stored.same(stored.load_outcome(path.stem), right)  # written again


def test_variants_are_read_back_as_solved_together(disk, forget, monkeypatch):
    problem = load_problem(COASTING)
    name = to_text(problem.givens[0].key.node)
    variants = overrides(problem, 0.9, 1.1, 1.2) + [{name: None}]  # the last one alone
    monkeypatch.setenv("MECHGRADE_NO_CACHE", "1")
    off = solve_variants(problem, variants)
    monkeypatch.delenv("MECHGRADE_NO_CACHE")
    forget()
    cold = solve_variants(problem, variants)
    # a class's generated mistakes are solved together when first read: read them before
    # solving is forbidden
    assert all(stored.same_outcome(a, b) for a, b in zip(off, cold))
    forget()
    monkeypatch.setattr(batch, "_template", not_solved)
    monkeypatch.setattr(entry, "_solve_dynamics", not_solved)
    warm = solve_variants(problem, variants)
    assert all(stored.same_outcome(b, c) for b, c in zip(cold, warm))
    assert isinstance(warm[-1], MechgradeError)  # without the given: solved alone, an error


def test_only_the_variants_not_stored_are_solved_and_equal_givens_once(disk, monkeypatch):
    problem = load_problem(COASTING)
    first, second, third = overrides(problem, 0.9, 1.1, 1.2)
    solve_variants(problem, [first, second])
    asked = []
    solved_together = batch._solved_together

    def spy(problem, given):
        asked.append(given)
        return solved_together(problem, given)

    monkeypatch.setattr(batch, "_solved_together", spy)
    out = solve_variants(problem, [second, third, first, third])
    assert asked == [[third]]
    assert out[1] is out[3]
    assert stored.same(out[0], solve_variants(problem, [second])[0])


def test_a_variant_not_read_back_whole_is_solved_again(disk, forget, entry_file):
    problem = load_problem(COASTING)
    variant = overrides(problem, 1.1)
    right = solve_variants(problem, variant)[0]
    key = stored.variant_keys(problem, variant)[0]
    entry_file(key).write_text("{truncated")
    forget()
    assert stored.same(solve_variants(problem, variant)[0], right)
    assert stored.same(stored.load_outcome(key), right)


def negated(data):
    """A solution's numbers changed: vectors turned round, scalars doubled."""
    for result in data["results"]:
        value = result["value"]
        result["value"] = [-v for v in value] if isinstance(value, list) else \
            None if value is None else 2 * value
    for state in data["state"]:
        state["value"] *= 2
    return data


@pytest.mark.slow
def test_edited_dynamics_numbers_are_not_trusted(disk, entry_file, rewrite_entry):
    problem = load_problem(HW3 / "pendulum_release.yaml")
    right = solve(problem)
    assert any(isinstance(r.value, tuple) for r in right.results)
    path = entry_file(stored.solution_key(problem, None, None))
    rewrite_entry(path, negated)
    assert stored.same(solve(problem), right)
    assert stored.same(stored.load_outcome(path.stem), right)  # written again


def test_an_edited_variant_is_not_trusted(disk, entry_file, rewrite_entry):
    problem = load_problem(COASTING)
    variant = overrides(problem, 1.1)
    right = solve_variants(problem, variant)[0]
    key = stored.variant_keys(problem, variant)[0]
    rewrite_entry(entry_file(key), negated)
    assert stored.same(solve_variants(problem, variant)[0], right)


def test_variants_of_a_problem_with_the_cache_off_are_not_kept(disk, monkeypatch):
    monkeypatch.setenv("MECHGRADE_NO_CACHE", "1")
    problem = load_problem(COASTING)
    solve_variants(problem, overrides(problem, 0.9, 1.1))
    assert not disk.exists()


@pytest.mark.slow  # two whole-class gradings of hw3
def test_a_second_grading_run_derives_nothing_and_writes_the_same_results(twice, tmp_path):
    # sympy itself is imported all the same: the sandboxes judging symbolic answers load it
    script = (
        "import hashlib, sys, tempfile\n"
        "from pathlib import Path\n"
        "from mechgrade.cli.common import main\n"
        "out = Path(tempfile.mkdtemp())\n"
        f"hw = {str(HW3)!r}\n"
        "try:\n"
        f"    main(['grade', {str(PENDULUM_ONLY)!r}, hw + '/submissions', '--roster',\n"
        "          hw + '/roster.csv', '--out', str(out), '--jobs', '2'])\n"
        "except SystemExit as stop:\n"
        "    assert not stop.code, stop.code\n"
        "derived = sorted(m for m in sys.modules if m in ('mechgrade.solve.dynamics',\n"
        "                 'mechgrade.solve.dynamics_mutants'))\n"
        "print(derived, hashlib.sha256((out / 'results.json').read_bytes()).hexdigest())\n")
    cold, warm = (run.splitlines()[-1].rsplit(" ", 1) for run in twice(script))
    assert cold[0] != "[]" and warm[0] == "[]"
    off = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         env=dict(os.environ, MECHGRADE_NO_CACHE="1"), check=True)
    assert cold[1] == warm[1] == off.stdout.splitlines()[-1].rsplit(" ", 1)[1]


def test_a_dynamics_problems_kinematic_mistakes_are_generated_with_the_cache_on_as_off(
        disk, forget, monkeypatch):
    # the plan of its kinematic part, read from the cache, compiled the mutations of that
    # part's objectives (none): ω × r left out, another point's velocity... were lost
    problem = load_problem(ROOT / "problems" / "rod_struck_on_ice.yaml")
    on = solve(problem).result("vB_after").generated_mistakes
    forget()
    monkeypatch.setenv("MECHGRADE_NO_CACHE", "1")
    off = solve(problem).result("vB_after").generated_mistakes
    assert {"other_point", "drop_omega_r"} <= {m.code for m in off}
    assert list(on) == list(off)
