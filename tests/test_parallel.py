"""Work over forked processes: results in order, errors as in a plain loop, dead workers redone."""

from __future__ import annotations

import os
import textwrap
from functools import partial

import pytest

from mechgrade.errors import Location, SpecError
from mechgrade.parallel import Forked, fork_map, outcome, raise_first


def square_or_fail(n: int) -> int:
    if n < 0:
        raise SpecError(f"expected a natural number, found {n}", where=Location("f.yaml", n))
    return n * n


def pid_of(_: int) -> int:
    return os.getpid()


def die_in_a_worker(parent: int, n: int) -> int:
    if os.getpid() != parent and n == 2:
        os._exit(1)
    return n


def test_results_keep_the_order_of_the_work():
    assert fork_map(square_or_fail, range(20), jobs=3) == [n * n for n in range(20)]
    assert len(set(fork_map(pid_of, range(8), jobs=2)) - {os.getpid()}) >= 1


def test_one_job_runs_here():
    assert set(fork_map(pid_of, range(4), jobs=1)) == {os.getpid()}


def test_errors_come_back_whole_and_the_first_in_order_is_raised():
    work = [partial(square_or_fail, n) for n in (1, -3, -2)]
    outcomes = fork_map(outcome, work, jobs=2)
    assert outcomes[0] == 1 and str(outcomes[1]) == "f.yaml:-3: expected a natural number, found -3"
    with pytest.raises(SpecError, match="found -3"):
        raise_first(outcomes)


def test_work_of_a_dead_worker_is_done_here():
    assert fork_map(partial(die_in_a_worker, os.getpid()), range(5), jobs=2) == list(range(5))


def exit_unless_in(parent: int) -> int:
    if os.getpid() != parent:
        os._exit(1)
    return 7


def test_forked_work_runs_elsewhere_and_its_value_comes_back():
    assert Forked(partial(pid_of, 0)).result() != os.getpid()


def test_forked_work_that_dies_or_fails_is_done_here_with_its_own_error():
    assert Forked(partial(exit_unless_in, os.getpid())).result() == 7
    with pytest.raises(ZeroDivisionError):
        Forked(lambda: 1 / 0).result()


def test_forked_work_can_be_stopped():
    import time

    forked = Forked(partial(time.sleep, 60))
    started = time.monotonic()
    forked.cancel()
    assert time.monotonic() - started < 10


# A parent killed with SIGKILL (the OOM killer) runs no clean-up: its workers must still go.
STAY = """
import os, sys, time
from functools import partial
from mechgrade.parallel import Forked, fork_map

def stay(n):
    print("a worker writing to the terminal", flush=True)
    time.sleep(600)
"""


def run_python(marked_run, script: str):
    import sys

    return marked_run([sys.executable, "-c", script])


def test_pool_workers_die_with_their_killed_parent(marked_run):
    run = run_python(marked_run, STAY + "fork_map(stay, range(4), jobs=2)\n")
    run.wait_for(lambda: len(run.workers()) >= 2)
    run.kill()
    assert run.survivors() == set()
    assert run.output_closed()


def test_forked_work_and_its_workers_die_with_their_killed_parent(marked_run):
    run = run_python(marked_run, STAY + "Forked(partial(fork_map, stay, range(4), jobs=2))\n"
                                        "time.sleep(600)\n")
    run.wait_for(lambda: len(run.workers()) >= 3)
    run.kill()
    assert run.survivors() == set()
    assert run.output_closed()


def test_a_parent_that_stops_on_an_error_leaves_no_worker_holding_its_output(marked_run,
                                                                           tmp_path):
    # The forked work is stopped, as on an internal error, and the parent exits: the pool the
    # work started must not live on, holding the terminal open.
    run = run_python(marked_run, STAY + textwrap.dedent(f"""\
        def stay_here(n):
            open(os.path.join({str(tmp_path)!r}, str(os.getpid())), "w").close()
            stay(n)

        forked = Forked(partial(fork_map, stay_here, range(4), jobs=2))
        while len(os.listdir({str(tmp_path)!r})) < 2:
            time.sleep(0.05)
        forked.cancel()
        sys.exit(3)
        """))
    assert run.process.wait(60) == 3
    assert run.survivors() == set()
    assert run.output_closed()
