"""Judging in a bounded worker: overruns become not_evaluated and the run goes on."""

import pytest

from mechgrade.grade.compare import Assessment, assess

from mechgrade.grade.policy import GradingPolicy
from mechgrade.grade.sandbox import Sandbox, SandboxPool, assess_batch, assess_bounded
from mechgrade.solve.result import ObjectiveResult

ACC = ObjectiveResult("acc", "scalar", "ft/s^2", 98.51)
SYM = ObjectiveResult("a_sym", "symbolic", "m/s^2", expr="L*sqrt(thetad**4 + thetadd**2)",
                      symbols=("L", "thetad", "thetadd"),
                      symbol_units=("m", "rad/s", "rad/s^2"))


def hostile_judge(text, result, policy):
    """Does what an unguarded sympy grader would do on some inputs."""
    if text == "hang":
        import sympy
        x = sympy.Symbol("x")
        sympy.simplify(sympy.expand((x + 1) ** 3000))
    if text == "spin":
        while True:
            pass
    if text == "memory":
        hog = bytearray(4 * 1024 ** 3)
        return Assessment("correct", 1.0, None, str(len(hog)), None)
    if text == "crash":
        raise RuntimeError("bug")
    if text == "exit":
        import os
        os._exit(3)
    return assess(text, result, policy)


def test_bounded_assessment_matches_direct_assessment():
    for text in ("98.5 ft/s^2", "-98.5 ft/s^2", "30 m/s", None, "__import__('os')"):
        assert assess_bounded(text, ACC, GradingPolicy(), seconds=20) == assess(text, ACC, GradingPolicy())


def test_batch_reuses_one_worker_and_matches_direct_assessment():
    items = [(t, SYM, GradingPolicy()) for t in ("L sqrt(θ̇^4+θ̈^2)", "L θ̇^2", "x", "9**9**9")]
    assert assess_batch(items, seconds=20) == [assess(*item) for item in items]


@pytest.mark.parametrize("text", ["hang", "spin"])
def test_overrun_is_not_evaluated_and_the_run_goes_on(text):
    with Sandbox(seconds=0.5, judge=hostile_judge) as box:
        first, killed, after = box.assess_many([("98.5 ft/s^2", ACC, GradingPolicy()),
                                                 (text, ACC, GradingPolicy()),
                                                 ("98.5 ft/s^2", ACC, GradingPolicy())])
        assert first.verdict == "correct" and after.verdict == "correct"
        assert killed.verdict == "not_evaluated" and killed.credit == 0.0
        assert "could not be evaluated" in killed.feedback and "not marked wrong" in killed.feedback
        assert box.restarts == 1


def test_memory_overrun_is_not_evaluated():
    with Sandbox(seconds=20, memory_mb=128, judge=hostile_judge) as box:
        judged = box.assess("memory", ACC)
        assert judged.verdict == "not_evaluated" and "128 MiB" in judged.feedback
        assert box.assess("98.5 ft/s^2", ACC).verdict == "correct"


@pytest.mark.parametrize("text", ["crash", "exit"])
def test_crashing_judge_is_not_evaluated(text):
    with Sandbox(seconds=20, judge=hostile_judge) as box:
        assert box.assess(text, ACC).verdict == "not_evaluated"
        assert box.assess("98.5 ft/s^2", ACC).verdict == "correct"


def test_worker_is_reused_without_restarts():
    with Sandbox(seconds=20) as box:
        box.assess_many([("98.5 ft/s^2", ACC, GradingPolicy())] * 20)
        assert box.restarts == 0


def test_sandbox_refuses_bad_limits():
    with pytest.raises(ValueError, match="positive time limit"):
        Sandbox(seconds=0)
    with pytest.raises(ValueError, match="positive memory limit"):
        Sandbox(memory_mb=-1)


MIXED = ["98.5 ft/s^2", "spin", "-98.5 ft/s^2", "crash", "30 m/s", "exit", "98.5", None,
         "1 ft", "spin", "98.6 ft/s^2"]


def test_pool_judges_in_item_order_like_one_worker():
    items = [(t, ACC, GradingPolicy()) for t in ("98.5 ft/s^2", "-98.5 ft/s^2", "30 m/s", None, "x")] * 7
    with SandboxPool(2, seconds=20) as pool:
        assert pool.assess_many(items) == [assess(*item) for item in items]
        assert pool.restarts == 0


def test_pool_bounds_every_answer_and_finishes_the_rest():
    items = [(t, ACC, GradingPolicy()) for t in MIXED]
    with SandboxPool(2, seconds=0.5, judge=hostile_judge) as pool:
        judged = pool.assess_many(items)
    verdicts = [a.verdict for a in judged]
    assert verdicts == [a.verdict for a in (assess(t, ACC, GradingPolicy()) if t not in
                                            ("spin", "crash", "exit") else
                                            Assessment("not_evaluated", 0.0, None, None, None)
                                            for t in MIXED)]
    assert "longer than 0.5 s" in judged[1].feedback and "stopped" in judged[5].feedback


def test_each_answer_of_a_batch_has_its_own_time_limit():
    import time

    def slow(text, result, policy):
        time.sleep(0.3)
        return assess(text, result, policy)

    with Sandbox(seconds=1.0, judge=slow) as box:
        judged = box.assess_many([("98.5 ft/s^2", ACC, GradingPolicy())] * 6)  # 1.8 s in all
        assert [a.verdict for a in judged] == ["correct"] * 6 and box.restarts == 0


def test_pool_refuses_no_workers():
    with pytest.raises(ValueError, match="positive number of workers"):
        SandboxPool(0)


def test_answers_in_flight_when_a_worker_dies_go_to_the_fresh_worker_in_order():
    texts = [f"{i} ft/s^2" for i in range(40)]
    for at in range(3, 40, 4):
        texts[at] = "exit"
    items = [(t, ACC, GradingPolicy()) for t in texts]
    with SandboxPool(2, seconds=20, judge=hostile_judge) as pool:
        judged = pool.assess_many(items)
    assert [(a.verdict, a.read_back) for a in judged] == [
        ("not_evaluated", None) if t == "exit" else (assess(t, ACC).verdict, assess(t, ACC).read_back)
        for t in texts]


def test_items_are_the_same_exactly_when_equal_whichever_objects_hold_them():
    from dataclasses import replace

    from mechgrade.grade.sandbox import _keys

    twin, other = replace(SYM), replace(SYM, unit="m")
    keys = _keys([("L", SYM, GradingPolicy()), ("L", twin, GradingPolicy()), ("L", other, GradingPolicy()),
                  ("2 L", SYM, GradingPolicy()), ("L", SYM, GradingPolicy(seed=1))])
    assert keys[0] == keys[1] and len(set(keys)) == 4


def test_idle_and_busy_workers_die_with_their_killed_parent(marked_run):
    # One worker waits for answers, the other is stuck in one: neither may outlive a parent
    # killed with SIGKILL (no clean-up runs), nor keep the parent's output open.
    import sys
    import textwrap

    run = marked_run([sys.executable, "-c", textwrap.dedent("""\
        import time
        from mechgrade.grade.policy import GradingPolicy
        from mechgrade.grade.sandbox import Sandbox
        from mechgrade.solve.result import ObjectiveResult

        def spin(text, result, policy):
            while True:
                pass

        acc = ObjectiveResult("acc", "scalar", "ft/s^2", 98.51)
        idle = Sandbox(seconds=600)
        idle.assess("98.5 ft/s^2", acc, GradingPolicy())
        Sandbox(seconds=600, judge=spin).assess("1 m", acc, GradingPolicy())
        """)])
    run.wait_for(lambda: len(run.workers()) >= 2)
    run.kill()
    assert run.survivors() == set()
    assert run.output_closed()


KEPT = []


def identity_judge(text, result, policy):
    """Tells which object the worker judged against (kept alive, so ids are not reused)."""
    KEPT.append(result)
    return Assessment("correct", 1.0, None, str(id(result)), None)


def test_a_worker_judges_every_answer_to_one_reference_against_one_object():
    # what compare works out once per objective is found again by the object's identity
    items = [(f"{i} ft/s^2", ACC, GradingPolicy()) for i in range(300)]
    with Sandbox(seconds=20, judge=identity_judge) as box:
        judged = box.assess_many(items) + box.assess_many(items[:10])
    assert len({a.feedback for a in judged}) == 1


def test_a_reference_travels_once_to_a_worker_then_by_its_number():
    policy = GradingPolicy()
    box = Sandbox(seconds=20)
    first = box.message([("1 m", ACC, policy), ("2 m", SYM, policy), ("3 m", ACC, policy)])
    second = box.message([("4 m", SYM, policy)])
    assert first == (False, [(0, ACC), (1, policy), (2, SYM)],
                     [("1 m", 0, 1), ("2 m", 2, 1), ("3 m", 0, 1)])
    assert second == (False, [], [("4 m", 2, 1)])


def test_a_worker_holding_too_many_references_forgets_them_and_is_sent_them_again(monkeypatch):
    from dataclasses import replace

    from mechgrade.grade import sandbox

    monkeypatch.setattr(sandbox, "MAX_HELD", 3)
    references, policy = [replace(ACC, value=98.51 * (1 + i)) for i in range(6)], GradingPolicy()
    items = [(f"{98.5 * (1 + i % 6)} ft/s^2", references[i % 6], policy) for i in range(60)]
    with Sandbox(seconds=20) as box:
        forgets = box.message(items[:6])[0], box.message(items[6:12])
        assert box.assess_many(items) == [assess(*item) for item in items]
    assert forgets[0] is False and forgets[1][0] is True and len(forgets[1][1]) == 7


def test_a_worker_sends_the_outcomes_of_quick_answers_in_groups(monkeypatch):
    from multiprocessing.connection import Connection

    received = []
    recv = Connection.recv
    monkeypatch.setattr(Connection, "recv", lambda self: received.append(1) or recv(self))
    items = [(f"{i} ft/s^2", ACC, GradingPolicy()) for i in range(400)]
    with Sandbox(seconds=20) as box:
        assert box.assess_many(items) == [assess(*item) for item in items]
    assert len(received) < len(items) / 4


def test_outcomes_judged_but_not_sent_when_a_worker_is_killed_are_judged_again():
    # the quick answers before "spin" are judged within one group, which the kill loses
    texts = ["98.5 ft/s^2", "-98.5 ft/s^2", "30 m/s", "spin", "98.5", "1 ft"]
    with Sandbox(seconds=0.5, judge=hostile_judge) as box:
        judged = box.assess_many([(t, ACC, GradingPolicy()) for t in texts])
        assert box.restarts == 1
    assert [a.verdict for a in judged] == [
        "not_evaluated" if t == "spin" else assess(t, ACC).verdict for t in texts]
    assert "longer than 0.5 s" in judged[3].feedback


def test_an_answer_that_runs_out_of_memory_after_quick_ones_is_the_one_not_evaluated():
    texts = ["98.5 ft/s^2", "-98.5 ft/s^2", "memory", "30 m/s"]
    with Sandbox(seconds=20, memory_mb=128, judge=hostile_judge) as box:
        judged = box.assess_many([(t, ACC, GradingPolicy()) for t in texts])
    assert [a.verdict for a in judged] == [
        "not_evaluated" if t == "memory" else assess(t, ACC).verdict for t in texts]
    assert "128 MiB" in judged[2].feedback


def test_the_batches_a_worker_is_handed_at_once_travel_as_one_message():
    from mechgrade.grade.sandbox import MAX_BATCH, _Spread

    class Recording(Sandbox):
        """Keeps what it is handed instead of starting a worker."""

        def _send(self, batch):
            handed.append(len(batch))
            return True

    handed: list[int] = []
    box = Recording(seconds=20)
    _Spread([box], [(f"{i} ft/s^2", ACC, GradingPolicy()) for i in range(400)]).refill(box)
    assert handed == [MAX_BATCH + MAX_BATCH]  # a batch to judge and one beyond, in one message
