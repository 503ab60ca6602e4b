"""The disk cache of compiled problems: a problem read back from it solves exactly as one
derived with sympy, without sympy; an entry is found only under its own problem and versions;
an entry that is corrupt, truncated, foreign or tampered with is ignored and written again."""

from __future__ import annotations

import itertools
import json
import os
from dataclasses import replace
from pathlib import Path

import pytest

import mechgrade.solve.cache as cache
from mechgrade.solve import kinematics_plan, solve
from mechgrade.solve.mutants import inside_tolerance
from mechgrade.spec import load_problem, load_problem_text

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "problems"
PENDULUM = PROBLEMS / "bowling_3_15_4_pendulum.yaml"
BASE = (ROOT / "tests" / "data" / "spec" / "base.yaml").read_text()

# A representative set (the whole of problems/ takes a minute): a symbolic objective, vector
# objectives, non-linear position levels, a gear train, rolling, a path (n-t) problem, an
# objective with givens of its own, and dynamics problems (whose solution is cached).
REPRESENTATIVE = [
    "bowling_3_15_2_cannonball.yaml", "bowling_3_15_3_mass_spring_damper.yaml",
    "bowling_3_15_4_pendulum.yaml", "bowling_3_15_6_gears.yaml",
    "bowling_3_15_7_rolling_ball_mound.yaml", "bowling_P3_17_rocking_block.yaml",
    "bowling_P3_8_planetary_gears.yaml", "ruina_10_10_collar_bent_arm.yaml",
    "ruina_10_3_spiral_bug.yaml", "ruina_10_5_rod_collar_disk.yaml",
    "ruina_10_6_rotating_tube_velocity.yaml", "ruina_10_9_unit_vector_rates.yaml",
    "ladder_wall_lift_off.yaml", "atwood_machine.yaml", "ruina_9_26_billiard_cue.yaml",
    "yo_yo_unwinding.yaml"]
LADDER = PROBLEMS / "ladder_wall_lift_off.yaml"


def comparable(solution):
    """A solution's content (an error compares by identity: by its message here)."""
    return (solution.problem, solution.results, solution.state, solution.dof,
            tuple((f.id, str(f.error)) for f in solution.failures), solution.warnings)


def entries(folder: Path) -> list[Path]:
    return sorted(folder.glob("*.json"))


@pytest.mark.parametrize("name", REPRESENTATIVE)
def test_a_problem_read_back_from_the_cache_solves_as_one_derived(name, disk, monkeypatch, forget):
    problem = load_problem(PROBLEMS / name)
    monkeypatch.setenv("MECHGRADE_NO_CACHE", "1")
    derived = comparable(solve(problem))
    monkeypatch.delenv("MECHGRADE_NO_CACHE")
    forget()
    cold = comparable(solve(problem))  # derived, then written
    assert entries(disk)
    forget()
    warm = comparable(solve(problem))  # read back
    assert derived == cold == warm


def test_a_plan_read_back_is_not_derived_until_its_kinematics_are_asked_for(disk, forget):
    problem = load_problem(PENDULUM)
    solve(problem)  # its plan and symbolic answers written
    first = kinematics_plan(problem)
    forget()
    again = kinematics_plan(problem)
    assert "k" in vars(first) and "k" not in vars(again)
    solve(problem)
    assert "k" not in vars(again)
    assert again.k.coordinates == first.k.coordinates  # derived when read
    assert again.index.symbols == first.index.symbols


@pytest.mark.parametrize("path", [PENDULUM, LADDER], ids=["kinematics", "dynamics"])
def test_a_warm_solve_imports_no_sympy(path, twice):
    # solve itself, not check: check's own report cache would answer before any plan is read
    runs = twice("import sys\n"
                 "from mechgrade.solve import solve\n"
                 "from mechgrade.spec import load_problem\n"
                 f"solution = solve(load_problem({str(path)!r}))\n"
                 "assert solution.results and not solution.failures, solution\n"
                 "print(sorted(m for m in sys.modules if m.split('.')[0] == 'sympy')[:3])\n")
    assert runs[0] != "[]"  # cold: derived with sympy
    assert runs[1] == "[]"


def test_cached_mistakes_and_symbolic_answers_are_those_derived(disk, forget):
    problem = load_problem(PENDULUM)
    cold = solve(problem)
    forget()
    warm = solve(problem)
    assert [m.code for m in inside_tolerance(warm.result("acc_mag"))] == ["drop_tangential"]
    assert warm.result("acc_mag_symbolic") == cold.result("acc_mag_symbolic")
    assert warm.result("acc_mag_symbolic").generated_mistakes


def test_the_key_changes_with_a_given_an_objective_and_the_versions(monkeypatch):
    text = BASE + ("  - {id: vel, prompt: Speed of P., find: \"mag(vel(P, N))\", "
                   "kind: scalar, unit: m/s}\n")
    key = cache.problem_key(load_problem_text(text, "p.yaml"))
    assert cache.problem_key(load_problem_text(text, "p.yaml")) == key
    other_given = text.replace("L: 2 m", "L: 3 m")
    assert other_given != text
    assert cache.problem_key(load_problem_text(other_given, "p.yaml")) != key
    other_objective = text.replace("mag(vel(P, N))", "dot(vel(P, N), N.x)")
    assert cache.problem_key(load_problem_text(other_objective, "p.yaml")) != key
    assert cache.problem_key(load_problem_text(text, "q.yaml")) != key  # its locations
    monkeypatch.setattr(cache, "__version__", "99.0")
    assert cache.problem_key(load_problem_text(text, "p.yaml")) != key
    monkeypatch.undo()
    monkeypatch.setattr(cache, "_sympy_version", lambda: "0.0")
    assert cache.problem_key(load_problem_text(text, "p.yaml")) != key


def test_the_cache_folder_follows_the_environment(monkeypatch, tmp_path):
    monkeypatch.delenv("MECHGRADE_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert cache.folder() == tmp_path / "mechgrade"
    monkeypatch.setenv("MECHGRADE_CACHE_DIR", str(tmp_path / "mine"))
    assert cache.folder() == tmp_path / "mine"
    monkeypatch.setenv("MECHGRADE_NO_CACHE", "1")
    assert not cache.enabled()
    monkeypatch.setenv("MECHGRADE_NO_CACHE", "0")
    assert cache.enabled()


def test_with_the_cache_off_nothing_is_written(disk, monkeypatch):
    monkeypatch.setenv("MECHGRADE_NO_CACHE", "1")
    solve(load_problem(PENDULUM))
    assert not disk.exists()


def test_a_cache_that_cannot_be_written_is_no_error(tmp_path, monkeypatch, forget):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.delenv("MECHGRADE_NO_CACHE", raising=False)
    monkeypatch.setenv("MECHGRADE_CACHE_DIR", str(blocker / "cache"))
    forget()
    assert round(solve(load_problem(PENDULUM)).result("acc_mag").value, 2) == 98.51
    forget()


def spoil_plan(disk: Path, problem, spoil) -> None:
    """Rewrite the problem's plan entry with ``spoil(text) -> text``."""
    path = disk / f"{cache.problem_key(problem)}.json"
    path.write_text(spoil(path.read_text()))


def tampered_source(text: str) -> str:
    entry = json.loads(text)
    entry["data"]["objectives"][0][1] = ("def f(*a):\n    return __import__('os').system("
                                         "'touch pwned')\n")
    return json.dumps(entry)


def wrong_numbers(text: str) -> str:
    """Valid source that the checks pass, but the entry is another key's."""
    entry = json.loads(text)
    entry["key"] = "0" * 64
    return json.dumps(entry)


@pytest.mark.parametrize("spoil", [
    lambda text: text[:len(text) // 2],  # truncated
    lambda text: "\x00\xff garbage",  # corrupt
    lambda text: "[]",  # not an entry
    lambda text: text.replace(f'"format":{cache.FORMAT}', '"format":0'),  # another format
    lambda text: text.replace('"index":[', '"index":[[],'),  # another layout
    wrong_numbers,  # another problem's
    tampered_source,  # code that is not numpy arithmetic
], ids=["truncated", "corrupt", "not-an-entry", "format", "layout", "foreign", "tampered"])
def test_a_spoilt_entry_is_ignored_and_written_again(spoil, disk, tmp_path, monkeypatch, forget):
    monkeypatch.chdir(tmp_path)
    problem = load_problem(PENDULUM)
    right = comparable(solve(problem))
    spoil_plan(disk, problem, spoil)
    forget()
    assert comparable(solve(problem)) == right
    assert not (tmp_path / "pwned").exists()
    forget()
    assert "k" not in vars(kinematics_plan(problem))  # written again: read back whole this time


def test_an_entry_of_another_problem_under_this_ones_name_is_not_used(disk, forget):
    pendulum = load_problem(PENDULUM)
    other = load_problem(PROBLEMS / "bowling_3_15_2_cannonball.yaml")
    right = comparable(solve(pendulum))
    solve(other)
    (disk / f"{cache.problem_key(other)}.json").replace(
        disk / f"{cache.problem_key(pendulum)}.json")
    forget()
    assert comparable(solve(pendulum)) == right


def test_a_symbolic_answer_entry_that_is_spoilt_is_derived_again(disk, forget):
    problem = load_problem(PENDULUM)
    right = solve(problem).result("acc_mag_symbolic")
    plan_file = disk / f"{cache.problem_key(problem)}.json"
    for path in entries(disk):
        if path != plan_file:
            path.write_text('{"format": %d, "key": "%s", "data": {"id": 3}}'
                            % (cache.FORMAT, path.stem))
    forget()
    assert solve(problem).result("acc_mag_symbolic") == right


@pytest.mark.parametrize("source, why", [
    ("import os\n", "expected one function definition"),
    ("def f(x):\n    return x.__class__\n", "Attribute is not allowed"),
    ("def f(x):\n    return open('f')\n", "only calls of numpy functions are allowed"),
    ("def f(x):\n    return y\n", "name 'y' is not allowed"),
    ("def f(x):\n    return 'text'\n", "only numeric constants are allowed"),
    ("def f(x):\n    return [i for i in x]\n", "is not allowed"),
    ("def f(x):\n    x[0] = 1\n    return x\n", "statement Assign is not allowed"),
    ("def f(x):\n    return sin(x)(x)\n", "only calls of numpy functions are allowed"),
    ("def f(x, *a):\n    return x\n", "plain positional arguments"),
    ("def f(x):\n    pass\n", "end in a return"),
])
def test_generated_source_other_than_numpy_arithmetic_is_refused(source, why):
    with pytest.raises(cache.UnsafeSource, match=why):
        cache.numpy_function(source)


def test_a_problem_without_a_canonical_text_is_not_cached(disk):
    problem = load_problem(PENDULUM)
    odd = replace(problem, statement=object())  # type: ignore[arg-type]
    assert cache.problem_key(odd) is None


def aged(disk: Path, names: str, size: int = 1000) -> None:
    """An entry per letter of ``names`` of about ``size`` bytes, each used after the one
    before."""
    for age, name in enumerate(names):
        cache.store(name * 64, "x" * size)
        os.utime(disk / f"{name * 64}.json", ns=(0, (1_000_000 + age) * 10**9))


def kept(disk: Path) -> str:
    return "".join(sorted(p.name[0] for p in entries(disk)))


def test_pruning_removes_the_least_recently_used_entries(disk):
    aged(disk, "abcde")
    size = (disk / f"{'a' * 64}.json").stat().st_size
    cache.prune(5 * size)
    assert kept(disk) == "abcde"  # within the bound: nothing removed
    cache.prune(4 * size)
    assert kept(disk) == "cde"  # down to three quarters of the bound
    cache.prune(0)
    assert kept(disk) == ""


def test_an_entry_read_counts_as_used(disk):
    aged(disk, "abc")
    size = (disk / f"{'a' * 64}.json").stat().st_size
    assert cache.load("a" * 64) == "x" * 1000
    cache.prune(2 * size)
    assert kept(disk) == "a"


def test_an_entry_gone_while_pruning_is_no_error(disk, monkeypatch):
    aged(disk, "abcd")
    size = (disk / f"{'a' * 64}.json").stat().st_size
    remove = os.remove

    def raced(path):  # another process pruned the oldest one first
        remove(path)
        if Path(path).name.startswith("a"):
            raise FileNotFoundError(path)

    monkeypatch.setattr(os, "remove", raced)
    cache.prune(3 * size)
    assert kept(disk) == "cd"


def test_the_folder_is_pruned_on_a_process_first_store_and_every_so_many(disk, monkeypatch):
    bounds = []
    monkeypatch.setattr(cache, "prune", bounds.append)
    monkeypatch.setattr(cache, "_stores", itertools.count())
    monkeypatch.setenv("MECHGRADE_CACHE_MAX_MB", "0.5")
    for n in range(2 * cache.PRUNE_EVERY + 1):
        cache.store(f"{n:064d}", n)
    assert bounds == [512 * 1024] * 3


@pytest.mark.parametrize("value, megabytes", [
    (None, cache.MAX_MB), ("", cache.MAX_MB), ("50", 50), ("0", 0), ("lots", cache.MAX_MB)])
def test_the_size_bound_follows_the_environment(value, megabytes, monkeypatch):
    if value is None:
        monkeypatch.delenv("MECHGRADE_CACHE_MAX_MB", raising=False)
    else:
        monkeypatch.setenv("MECHGRADE_CACHE_MAX_MB", value)
    assert cache.limit() == megabytes * 1024 * 1024


def test_a_dynamics_solution_entry_in_a_small_cache_is_pruned_and_solved_again(
        disk, forget, monkeypatch):
    problem = load_problem(LADDER)
    right = comparable(solve(problem))
    cache.prune(0)
    assert not entries(disk)
    forget()
    assert comparable(solve(problem)) == right
    assert entries(disk)
