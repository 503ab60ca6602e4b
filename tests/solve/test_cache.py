"""The disk cache of compiled problems: a problem read back from it solves exactly as one
derived with sympy, without sympy; an entry is found only under its own problem and versions;
an entry that is corrupt, truncated, foreign or tampered with is ignored and written again."""

from __future__ import annotations

import contextlib
import hmac
import itertools
import os
import signal
import stat
import subprocess
import sys
from dataclasses import replace
from pathlib import Path
from typing import Callable

import pytest

import mechgrade.solve.cache as cache
from mechgrade.errors import SettingError
from mechgrade.solve import kinematics_plan, solve
from mechgrade.solve.instant import _bearing_givens
from mechgrade.solve.mutants import inside_tolerance
from mechgrade.solve.symbolic import bearing_givens
from mechgrade.spec import load_problem, load_problem_text

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "problems"
PENDULUM = PROBLEMS / "bowling_3_15_4_pendulum.yaml"
BASE = (ROOT / "tests" / "data" / "spec" / "base.yaml").read_text()

# A representative set (the whole of problems/ takes a minute): a symbolic objective, vector
# objectives, non-linear position levels, a gear train, rolling, a path (n-t) problem, an
# objective with givens of its own, and dynamics problems (whose solution is cached).
SLOWEST = ("bowling_P3_17_rocking_block.yaml", "bowling_P3_8_planetary_gears.yaml",
           "ruina_10_10_collar_bent_arm.yaml", "ruina_10_5_rod_collar_disk.yaml",
           "ladder_wall_lift_off.yaml", "atwood_machine.yaml", "yo_yo_unwinding.yaml",
           "ruina_9_26_billiard_cue.yaml")  # over 2 s each: `pytest -m slow` reads them back
REPRESENTATIVE = [pytest.param(name, marks=pytest.mark.slow) if name in SLOWEST else name
                  for name in [
    "bowling_3_15_2_cannonball.yaml", "bowling_3_15_3_mass_spring_damper.yaml",
    "bowling_3_15_4_pendulum.yaml", "bowling_3_15_6_gears.yaml",
    "bowling_3_15_7_rolling_ball_mound.yaml", "bowling_P3_17_rocking_block.yaml",
    "bowling_P3_8_planetary_gears.yaml", "ruina_10_10_collar_bent_arm.yaml",
    "ruina_10_3_spiral_bug.yaml", "ruina_10_5_rod_collar_disk.yaml",
    "ruina_10_6_rotating_tube_velocity.yaml", "ruina_10_9_unit_vector_rates.yaml",
    "ladder_wall_lift_off.yaml", "atwood_machine.yaml", "ruina_9_26_billiard_cue.yaml",
    "yo_yo_unwinding.yaml"]]
# integrates to an event, and its derivation and generated mistakes are quick to derive
COASTING = PROBLEMS / "boat_coasting_quadratic_drag.yaml"


def comparable(solution):
    """A solution's content (an error compares by identity: by its message here)."""
    return (solution.problem, solution.results, solution.state, solution.dof,
            tuple((f.id, str(f.error)) for f in solution.failures), solution.warnings)


def entries(folder: Path) -> list[Path]:
    return sorted((folder / "entries").glob("*.json"))


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


@pytest.mark.parametrize("path", [pytest.param(PENDULUM, marks=pytest.mark.slow), COASTING],
                         ids=["kinematics", "dynamics"])
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


@pytest.mark.parametrize("spoilt", [{"bearing": 3}, {"bearing": [1]}, ["acc"], {}])
def test_a_spoilt_entry_of_the_givens_an_answer_bears_on_is_read_again(spoilt, disk, forget):
    problem = load_problem(PENDULUM)
    right = solve(problem).result("acc_mag_symbolic")
    key = cache.digest("bearing", cache.problem_key(problem), "acc_mag_symbolic")
    assert isinstance(cache.load(key), dict)
    cache.store(key, spoilt)
    forget()
    assert _bearing_givens(problem, "acc_mag_symbolic") == \
        bearing_givens(problem, "acc_mag_symbolic")
    assert cache.load(key) == {"bearing": sorted(bearing_givens(problem, "acc_mag_symbolic"))}
    forget()
    assert solve(problem).result("acc_mag_symbolic") == right


def test_cached_mistakes_and_symbolic_answers_are_those_derived(disk, forget):
    problem = load_problem(PENDULUM)
    cold = solve(problem)
    forget()
    warm = solve(problem)
    # a_n for |a| is the same value as α × r left out: both families kept
    # theta'' taken as zero leaves the same normal acceleration as the tangential term dropped
    assert [m.code for m in inside_tolerance(warm.result("acc_mag"))] == [
        "drop_tangential", "acc_n_for_acc", "given_acceleration_zero"]
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


def plan_file(disk: Path, problem) -> Path:
    return disk / "entries" / f"{cache.problem_key(problem)}.json"


def tampered_source(entry: dict) -> dict:
    entry["objectives"][0][1] = ("def f(*a):\n    return __import__('os').system("
                                 "'touch pwned')\n")
    return entry


@pytest.mark.parametrize("spoil", [  # the first two read as the third: `pytest -m slow`
    pytest.param(lambda text: text[:len(text) // 2], marks=pytest.mark.slow),  # truncated
    pytest.param(lambda text: b"[]", marks=pytest.mark.slow),  # not an entry
    lambda text: b"\x00\xff garbage",  # corrupt
    lambda text: text.replace(b'"index":[', b'"index":[[],'),  # edited, without the key
], ids=["truncated", "not-an-entry", "corrupt", "edited"])
def test_a_spoilt_entry_is_ignored_and_written_again(spoil, disk, tmp_path, monkeypatch, forget):
    monkeypatch.chdir(tmp_path)
    problem = load_problem(PENDULUM)
    right = comparable(solve(problem))
    path = plan_file(disk, problem)
    path.write_bytes(spoil(path.read_bytes()))
    forget()
    assert comparable(solve(problem)) == right
    forget()
    assert "k" not in vars(kinematics_plan(problem))  # written again: read back whole this time


@pytest.mark.parametrize("spoil", [
    lambda entry: {**entry, "index": [[], *entry["index"]]},  # another layout
    tampered_source,  # code that is not numpy arithmetic
], ids=["layout", "tampered"])
def test_an_entry_signed_with_the_key_but_not_one_this_code_wrote_is_written_again(
        spoil, disk, tmp_path, monkeypatch, forget, rewrite_entry):
    monkeypatch.chdir(tmp_path)
    problem = load_problem(PENDULUM)
    right = comparable(solve(problem))
    rewrite_entry(plan_file(disk, problem), spoil, signed=True)
    forget()
    assert comparable(solve(problem)) == right
    assert not (tmp_path / "pwned").exists()
    forget()
    assert "k" not in vars(kinematics_plan(problem))


@pytest.mark.parametrize("spoil", [
    lambda entry: {**entry, "constraint_rank": str(entry["constraint_rank"])},  # "2", not 2
    lambda entry: {**entry, "levels": [{**entry["levels"][0], "linear": "no"},
                                       *entry["levels"][1:]]},  # a text that bool() reads True
    lambda entry: {**entry, "points": [3, *entry["points"]]},  # a number for a point's name
], ids=["rank-as-text", "linear-as-text", "point-as-number"])
def test_an_entry_whose_fields_are_of_other_types_is_written_again(
        spoil, disk, tmp_path, monkeypatch, forget, rewrite_entry):
    monkeypatch.chdir(tmp_path)
    problem = load_problem(PENDULUM)
    right = comparable(solve(problem))
    path = plan_file(disk, problem)
    written = path.read_bytes()
    rewrite_entry(path, spoil, signed=True)
    forget()
    assert comparable(solve(problem)) == right
    assert path.read_bytes().split(b"\n", 1)[1] == written.split(b"\n", 1)[1]


def test_an_entry_of_another_problem_under_this_ones_name_is_not_used(disk, forget):
    pendulum = load_problem(PENDULUM)
    other = load_problem(PROBLEMS / "bowling_3_15_2_cannonball.yaml")
    right = comparable(solve(pendulum))
    solve(other)
    plan_file(disk, other).replace(plan_file(disk, pendulum))
    forget()
    assert comparable(solve(pendulum)) == right


def test_a_symbolic_answer_entry_that_is_spoilt_is_derived_again(disk, forget, rewrite_entry):
    problem = load_problem(PENDULUM)
    right = solve(problem).result("acc_mag_symbolic")
    for path in entries(disk):
        if path != plan_file(disk, problem):
            rewrite_entry(path, lambda data: {"id": 3}, signed=True)
    forget()
    assert solve(problem).result("acc_mag_symbolic") == right


def test_a_problem_without_a_canonical_text_is_not_cached(disk):
    problem = load_problem(PENDULUM)
    odd = replace(problem, statement=object())  # type: ignore[arg-type]
    assert cache.problem_key(odd) is None


def aged(disk: Path, names: str, size: int = 1000) -> None:
    """An entry per letter of ``names`` of about ``size`` bytes, each used after the one
    before."""
    for age, name in enumerate(names):
        cache.store(name * 64, "x" * size)
        os.utime(disk / "entries" / f"{name * 64}.json", ns=(0, (1_000_000 + age) * 10**9))


def kept(disk: Path) -> str:
    return "".join(sorted(p.name[0] for p in entries(disk)))


def test_pruning_removes_the_least_recently_used_entries(disk):
    aged(disk, "abcde")
    size = (disk / "entries" / f"{'a' * 64}.json").stat().st_size
    cache.prune(5 * size)
    assert kept(disk) == "abcde"  # within the bound: nothing removed
    cache.prune(4 * size)
    assert kept(disk) == "cde"  # down to three quarters of the bound
    cache.prune(0)
    assert kept(disk) == ""


def test_an_entry_read_counts_as_used(disk):
    aged(disk, "abc")
    size = (disk / "entries" / f"{'a' * 64}.json").stat().st_size
    assert cache.load("a" * 64) == "x" * 1000
    cache.prune(2 * size)
    assert kept(disk) == "a"


def test_an_entry_gone_while_pruning_is_no_error(disk, monkeypatch):
    aged(disk, "abcd")
    size = (disk / "entries" / f"{'a' * 64}.json").stat().st_size
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
    (None, cache.MAX_MB), ("", cache.MAX_MB), ("50", 50), ("0", 0), (" 0.5 ", 0.5),
    ("1e3", 1000)])
def test_the_size_bound_follows_the_environment(value, megabytes, monkeypatch):
    if value is None:
        monkeypatch.delenv("MECHGRADE_CACHE_MAX_MB", raising=False)
    else:
        monkeypatch.setenv("MECHGRADE_CACHE_MAX_MB", value)
    assert cache.limit() == megabytes * 1024 * 1024


def test_a_dynamics_solution_entry_in_a_small_cache_is_pruned_and_solved_again(
        disk, forget, monkeypatch):
    problem = load_problem(COASTING)
    right = comparable(solve(problem))
    cache.prune(0)
    assert not entries(disk)
    forget()
    assert comparable(solve(problem)) == right
    assert entries(disk)


# ---------------------------------------------------------------------------- hostile folders
# Whoever may write the cache folder must not be able to change an answer, hang a run, exhaust
# its memory or lose a file of the user's (issue 18).


def test_the_folder_its_entries_and_key_are_made_private(disk):
    cache.store("a" * 64, 1)
    assert stat.S_IMODE(disk.stat().st_mode) == 0o700
    assert stat.S_IMODE((disk / "entries").stat().st_mode) == 0o700
    key = disk / "entries" / "key"
    assert stat.S_IMODE(key.stat().st_mode) == 0o600 and len(key.read_bytes()) == 32
    assert cache.warning() is None


@pytest.mark.parametrize("mode", [0o777, 0o775, 0o757, 0o1777])
def test_a_folder_others_may_write_is_not_used_and_says_so(mode, disk):
    disk.mkdir()
    disk.chmod(mode)
    cache.store("a" * 64, 1)
    assert cache.load("a" * 64) is None
    assert list(disk.iterdir()) == []
    assert cache.warning() == (
        f"cache folder {disk} may be written by other users (mode {mode:o}): not using the "
        f"cache in this run (make it private with 'chmod 700 {disk}', or set "
        "MECHGRADE_CACHE_DIR to a private folder)")


def other_user(path: Path) -> None:
    if os.geteuid() != 0:
        pytest.skip("giving a file to another user takes root")
    os.chown(path, 4242, 4242, follow_symlinks=False)


def test_a_folder_of_another_user_is_not_used_and_says_so(disk):
    disk.mkdir(mode=0o700)
    other_user(disk)
    cache.store("a" * 64, 1)
    assert list(disk.iterdir()) == []
    assert cache.warning() == (
        f"cache folder {disk} belongs to another user (uid 4242): not using the cache in "
        "this run (set MECHGRADE_CACHE_DIR to a folder of your own)")


def test_an_entries_folder_that_is_a_link_is_not_used(disk, tmp_path):
    (tmp_path / "elsewhere").mkdir(mode=0o700)
    disk.mkdir(mode=0o700)
    (disk / "entries").symlink_to(tmp_path / "elsewhere")
    cache.store("a" * 64, 1)
    assert list((tmp_path / "elsewhere").iterdir()) == []
    assert cache.warning().startswith(f"cannot use the cache folder {disk} (")


def spoil_key(spoil):
    def spoilt(key: Path) -> None:
        key.unlink()
        spoil(key)
    return spoilt


@pytest.mark.parametrize("spoil, found", [
    (lambda key: key.chmod(0o644), "mode 644, 32 bytes"),
    (lambda key: key.chmod(0o660), "mode 660, 32 bytes"),
    (spoil_key(lambda key: (key.write_bytes(b"k" * 31), key.chmod(0o600))), "mode 600, 31 bytes"),
    (spoil_key(lambda key: key.mkdir()), "a folder"),
    (spoil_key(lambda key: os.mkfifo(key, 0o600)), "a special file"),
], ids=["readable", "group", "short", "folder", "pipe"])
def test_a_key_that_is_not_a_private_file_of_32_bytes_turns_the_cache_off(spoil, found, disk):
    cache.store("a" * 64, 1)
    spoil(disk / "entries" / "key")
    cache._state.cache_clear()  # a new process
    with bounded_time():
        assert cache.load("a" * 64) is None
    assert cache.warning() == (
        f"cache key {disk / 'entries' / 'key'} is not a private file of 32 bytes (found "
        f"{found}): not using the cache in this run (delete it: a new one is made)")


def test_a_key_that_is_a_link_or_another_users_turns_the_cache_off(disk, tmp_path):
    cache.store("a" * 64, 1)
    key = disk / "entries" / "key"
    (tmp_path / "copy").write_bytes(key.read_bytes())
    (tmp_path / "copy").chmod(0o600)
    key.unlink()
    key.symlink_to(tmp_path / "copy")
    cache._state.cache_clear()
    assert cache.load("a" * 64) is None
    assert cache.warning().startswith(f"cache key {key} cannot be read (")
    key.unlink()
    (tmp_path / "copy").rename(key)
    other_user(key)
    cache._state.cache_clear()
    assert cache.load("a" * 64) is None
    assert "belongs to another user (uid 4242)" in cache.warning()


def test_the_key_is_made_once_and_then_kept(disk):
    cache.store("a" * 64, 1)
    key = (disk / "entries" / "key").read_bytes()
    cache._state.cache_clear()
    assert cache.load("a" * 64) == 1
    assert (disk / "entries" / "key").read_bytes() == key


def test_an_entry_from_another_folder_is_not_trusted(tmp_path, monkeypatch, forget):
    monkeypatch.delenv("MECHGRADE_NO_CACHE", raising=False)
    monkeypatch.setenv("MECHGRADE_CACHE_DIR", str(tmp_path / "theirs"))
    cache.store("a" * 64, {"answer": 1})
    monkeypatch.setenv("MECHGRADE_CACHE_DIR", str(tmp_path / "mine"))
    cache.store("b" * 64, {"answer": 2})
    mine = tmp_path / "mine" / "entries"
    (tmp_path / "theirs" / "entries" / f"{'a' * 64}.json").replace(mine / f"{'a' * 64}.json")
    assert cache.load("a" * 64) is None and cache.load("b" * 64) == {"answer": 2}


class Hung(Exception):
    pass


@contextlib.contextmanager
def bounded_time(seconds: int = 20):
    """Fail instead of waiting for ever (a read that blocks)."""
    def hung(*_):
        raise Hung(f"still waiting after {seconds} s")
    previous = signal.signal(signal.SIGALRM, hung)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


def test_a_pipe_as_an_entry_is_a_miss_and_written_over(disk):
    cache.store("a" * 64, 1)
    path = disk / "entries" / f"{'a' * 64}.json"
    path.unlink()
    os.mkfifo(path, 0o600)
    with bounded_time():
        assert cache.load("a" * 64) is None
    cache.store("a" * 64, 1)
    assert path.is_file() and cache.load("a" * 64) == 1


def test_an_entry_linked_to_an_endless_file_is_a_miss(disk):
    # in a process of its own with its memory bounded: reading /dev/zero whole never ends
    cache.store("a" * 64, 1)
    path = disk / "entries" / f"{'a' * 64}.json"
    path.unlink()
    path.symlink_to("/dev/zero")
    script = ("import resource\n"
              "resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))\n"
              "from mechgrade.solve import cache\n"
              "print(cache.load('a' * 64))\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=120, env=dict(os.environ, MECHGRADE_CACHE_DIR=str(disk)))
    assert (done.returncode, done.stdout) == (0, "None\n"), done.stderr[-300:]
    assert path.is_symlink()


@pytest.mark.parametrize("body", [
    b"[" * 100_000 + b"]" * 100_000,  # nested past Python's recursion limit
    b'{"value": NaN}', b'{"value": Infinity}', b'{"value": 1e999}',  # not finite
    b'{"size": 1' + b"0" * 30 + b"}",  # a whole number no array can have
], ids=["deep", "nan", "infinity", "overflow", "huge-integer"])
def test_an_entry_signed_with_the_key_is_still_read_within_bounds(body, disk):
    cache.store("a" * 64, 1)
    path = disk / "entries" / f"{'a' * 64}.json"
    secret = (disk / "entries" / "key").read_bytes()
    mac = hmac.new(secret, b"a" * 64 + b"\n" + body, "sha256").hexdigest().encode()
    path.write_bytes(mac + b"\n" + body)
    assert cache.load("a" * 64) is None


def test_an_entry_larger_than_the_bound_is_neither_read_nor_written(disk, monkeypatch):
    monkeypatch.setattr(cache, "MAX_ENTRY_BYTES", 1000)
    cache.store("a" * 64, "x" * 2000)
    assert not (disk / "entries" / f"{'a' * 64}.json").exists()
    cache.store("a" * 64, "x" * 10)
    path = disk / "entries" / f"{'a' * 64}.json"
    monkeypatch.setattr(cache, "MAX_ENTRY_BYTES", 50)
    assert path.stat().st_size > 50 and cache.load("a" * 64) is None


def test_pruning_never_touches_a_file_the_cache_did_not_write(tmp_path, monkeypatch):
    course = tmp_path / "course"
    course.mkdir(mode=0o700)
    mine = {"results.json": "{}", "gradebook-backup.json": "[]", "settings.json": "{}",
            f"{'c' * 64}.json": "{}", "notes.txt": "keep"}
    for name, text in mine.items():
        (course / name).write_text(text)
    monkeypatch.delenv("MECHGRADE_NO_CACHE", raising=False)
    monkeypatch.setenv("MECHGRADE_CACHE_DIR", str(course))
    monkeypatch.setenv("MECHGRADE_CACHE_MAX_MB", "0")
    cache.store("a" * 64, "x" * 1000)
    stray = {"notes.json": "{}", f"{'D' * 64}.json": "{}", f"{'d' * 63}.json": "{}"}
    for name, text in stray.items():
        (course / "entries" / name).write_text(text)
    (course / "entries" / f"{'e' * 64}.json").symlink_to(course / "results.json")
    (course / "entries" / f"{'f' * 64}.json").mkdir()
    cache.prune(0)
    for name, text in mine.items():
        assert (course / name).read_text() == text
    for name, text in stray.items():
        assert (course / "entries" / name).read_text() == text
    assert (course / "entries" / f"{'e' * 64}.json").is_symlink()
    assert not (course / "entries" / f"{'a' * 64}.json").exists()  # its own entry: pruned


@pytest.mark.parametrize("value", ["nan", "inf", "-inf", "1e308", "-1", "abc", "1000001"])
def test_a_size_bound_that_is_not_a_number_of_megabytes_is_refused(value, monkeypatch):
    monkeypatch.setenv("MECHGRADE_CACHE_MAX_MB", value)
    with pytest.raises(SettingError) as refused:
        cache.limit()
    assert str(refused.value) == (
        f"MECHGRADE_CACHE_MAX_MB: expected a number of megabytes from 0 to 1000000, found "
        f"{value!r}; set it to a number such as 200, or unset it for the default (200)")


def test_a_bad_cache_setting_turns_the_cache_off_and_is_raised_by_warning(disk, monkeypatch):
    monkeypatch.setenv("MECHGRADE_CACHE_MAX_MB", "nan")
    cache.store("a" * 64, 1)  # no error: the library never stops on its cache
    assert cache.load("a" * 64) is None and not disk.exists()
    with pytest.raises(SettingError, match="MECHGRADE_CACHE_MAX_MB"):
        cache.warning()


def test_a_cache_folder_setting_that_is_relative_or_not_a_folder_is_refused(
        tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MECHGRADE_CACHE_DIR", "cache")
    with pytest.raises(SettingError) as relative:
        cache.folder()
    assert str(relative.value) == (
        f"MECHGRADE_CACHE_DIR: expected an absolute path to a folder, found 'cache'; write it "
        f"in full ({str(tmp_path / 'cache')!r}), or unset it for the default")
    (tmp_path / "file").write_text("x")
    monkeypatch.setenv("MECHGRADE_CACHE_DIR", str(tmp_path / "file"))
    with pytest.raises(SettingError) as file:
        cache.folder()
    assert str(file.value) == (
        f"MECHGRADE_CACHE_DIR: expected a folder, found a file that is not one: "
        f"{str(tmp_path / 'file')!r}; name a folder (it is made if missing), or unset it for "
        "the default")


def test_a_relative_xdg_cache_home_is_ignored(tmp_path, monkeypatch):
    monkeypatch.delenv("MECHGRADE_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", "relative")
    monkeypatch.setenv("HOME", str(tmp_path))
    assert cache.folder() == tmp_path / ".cache" / "mechgrade"


# ---------------------------------------------------------------------------- tampered answers


def half_of_the_first_objective(entry: dict) -> dict:
    _oid, source = entry["objectives"][0]
    head, _, value = source.rpartition("return ")
    entry["objectives"][0][1] = f"{head}return 0.5*({value.strip()})\n"
    return entry


def test_a_stored_function_edited_to_give_half_the_answer_is_not_trusted(
        disk, forget, rewrite_entry):
    problem = load_problem(PENDULUM)
    right = comparable(solve(problem))
    path = plan_file(disk, problem)
    rewrite_entry(path, half_of_the_first_objective)
    kinematics_plan.cache_clear()
    assert comparable(solve(problem)) == right
    forget()
    assert comparable(solve(problem)) == right  # written again, and read back
    assert "k" not in vars(kinematics_plan(problem))


def test_an_edited_symbolic_answer_is_not_trusted(disk, forget, rewrite_entry):
    problem = load_problem(PENDULUM)
    right = solve(problem).result("acc_mag_symbolic")
    edited = 0
    for path in entries(disk):
        if path != plan_file(disk, problem):
            rewrite_entry(path, lambda data: {**data, "expr": "2*L*thetad**2"})
            edited += 1
    assert edited
    forget()
    assert solve(problem).result("acc_mag_symbolic") == right


def test_a_kept_plan_entry_is_its_classs_fields_with_each_function_as_source():
    import dataclasses

    from mechgrade.solve.plan import Level, Mutant, _kept

    @dataclasses.dataclass(frozen=True)
    class Toy:
        name: str
        rate: Callable
        extra: Callable | None
        uses: tuple[int, ...]

    toy = _kept(Toy, "name")
    assert [(f.name, f.type) for f in dataclasses.fields(toy)] == [
        ("rate", str), ("extra", str | None), ("uses", tuple[int, ...])]
    assert toy.functions == {"rate", "extra"}
    for cls, left_out in ((Level, "name"), (Mutant, "objective")):
        assert [f.name for f in dataclasses.fields(_kept(cls, left_out))] == [
            f.name for f in dataclasses.fields(cls) if f.name != left_out]
