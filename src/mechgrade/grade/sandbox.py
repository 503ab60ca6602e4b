"""Judge answers in a worker process with a memory limit and a wall-clock kill.

sympy can hang in C-level loops or huge integer arithmetic (``9**9**9``, ``factorial(10**9)``,
``simplify`` of ``(x+1)**3000``, even ``str()`` of some results) and no thread timeout can stop
that. So answers are judged in a worker process, forked after sympy and the unit registry are
imported (the fork inherits them, so starting a worker costs milliseconds, not seconds). The
worker limits its address space (``RLIMIT_AS``); the parent waits at most ``seconds`` per answer
and kills the worker on overrun. An overrun gives the verdict ``not_evaluated`` ("could not be
evaluated", never "wrong") and the run goes on with a fresh worker; a worker is reused for many
answers and replaced only after a kill or a crash. Answers travel in batches and their outcomes
in groups (one round trip for many answers, each still timed on its own), and a
:class:`SandboxPool` runs a worker per core.

>>> from mechgrade.solve.result import ObjectiveResult
>>> acc = ObjectiveResult("a", "scalar", "ft/s^2", 98.51)
>>> assess_bounded("98.5 ft/s^2", acc, GradingPolicy(), seconds=10, memory_mb=512).verdict
<Verdict.CORRECT: 'correct'>
"""

from __future__ import annotations

import gc
import multiprocessing
import os
import select
import signal
import time
from collections import deque
from multiprocessing.connection import Connection
from multiprocessing.process import BaseProcess
from enum import Enum
from typing import Callable, Iterable, Sequence, Union, cast

from ..parallel import worker_started
from ..solve.result import ObjectiveResult
from .compare import Assessment, assess, not_evaluated
from .policy import GradingPolicy

Judge = Callable[[str | None, ObjectiveResult, GradingPolicy], Assessment]
Item = tuple[str | None, ObjectiveResult, GradingPolicy]


class Stopped(Enum):
    """What a worker sends instead of an answer's assessment when it stops."""

    OUT_OF_MEMORY = "out of memory"


Reply = Union[Assessment, Stopped]
"""What the worker sends for one answer: its assessment (``not_evaluated``, with the reason,
when judging failed), or :attr:`Stopped.OUT_OF_MEMORY`."""

DEFAULT_SECONDS = 5.0
DEFAULT_MEMORY_MB = 512


def _warm() -> None:
    """Import what judging needs before forking, so every worker inherits it."""
    import sympy  # noqa: F401 - imported for its effect: loaded once, before the fork

    from ..units import registry
    registry()


def _mapped_bytes() -> int | None:
    try:
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("VmSize:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return None


def _limit_memory(memory_mb: int) -> None:
    """Cap the address space at what is mapped now plus ``memory_mb`` MiB of headroom."""
    try:
        import resource
    except ImportError:  # pragma: no cover - not on POSIX
        return
    mapped = _mapped_bytes() or 0
    limit = mapped + memory_mb * 1024 * 1024
    try:
        _soft, hard = resource.getrlimit(resource.RLIMIT_AS)
        if hard != resource.RLIM_INFINITY:
            limit = min(limit, hard)
        resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    except (ValueError, OSError):  # pragma: no cover - the limit could not be lowered
        pass


Message = tuple[bool, list[tuple[int, object]], list[tuple[str | None, int, int]]]
"""A batch as it travels to the worker (:meth:`Sandbox.message`): whether the worker forgets
the references it holds, the references it has not been sent yet, each with its number, and
the answers, each ``(text, number of its reference, number of its policy)``."""

MAX_HELD = 1024
"""Most references and policies a worker holds; beyond, it forgets them all and is sent
afresh those it is asked about."""


GROUP_SECONDS = 0.002
"""How much judging a worker's outcomes gather before it sends them: one message (one
wake-up of the parent) for every answer judged in that time, or at once when it has nothing
more to judge. A worker judges an answer in a fraction of a millisecond, and on a busy machine
the parent's wake-ups and the messages took the workers' cores. The parent learns which answer
a worker is judging from its :class:`Progress`, without a message, so each answer still has
its own time limit, and the outcomes of a killed worker not yet sent (at most this much
judging) are judged again by the fresh one."""


class Progress:
    """What a worker is doing, in memory it shares with the parent: how many answers it has
    begun and when it began the last (``time.monotonic``), written before each answer without
    a system call.

    >>> progress = Progress(multiprocessing.get_context())
    >>> progress.begin()
    >>> progress.read()[0]
    1
    """

    def __init__(self, context) -> None:
        self._shared = context.RawArray("d", 2)

    def begin(self) -> None:
        """In the worker: one more answer begins now."""
        self._shared[1] = time.monotonic()
        self._shared[0] += 1

    def read(self) -> tuple[int, float]:
        """How many answers the worker has begun, and when it began the last."""
        return int(self._shared[0]), self._shared[1]


def _judged(judge: Judge, text: str | None, result: ObjectiveResult,
            policy: GradingPolicy) -> Reply:
    """``judge``'s assessment, ``not_evaluated`` when judging fails, or
    :attr:`Stopped.OUT_OF_MEMORY`."""
    try:
        return judge(text, result, policy)
    except MemoryError:
        return Stopped.OUT_OF_MEMORY
    except RecursionError:
        return not_evaluated("the expression is nested too deeply to evaluate")
    except Exception as exc:  # noqa: BLE001 - any failure is "could not be evaluated"
        return not_evaluated(f"{type(exc).__name__} while judging")


def _worker(conn: Connection, judge: Judge, memory_mb: int, progress: Progress) -> None:
    """Judge each batch of items sent, one answer at a time, saying in ``progress`` which
    answer it begins, and send the outcomes back in order, in groups (:data:`GROUP_SECONDS`)."""
    worker_started()
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent decides when we stop
    _limit_memory(memory_mb)
    held: dict[int, object] = {}  # the references and policies sent, by their numbers
    replies: list[Reply] = []  # judged, not sent yet
    began = 0.0  # when the first of them began
    while True:
        try:
            message: Message | None = conn.recv()
        except (EOFError, OSError):
            return
        if message is None:
            return
        forget, new, numbered = message
        if forget:
            held.clear()
        held.update(new)
        for text, r, p in numbered:
            progress.begin()
            if not replies:
                began = time.monotonic()
            replies.append(_judged(judge, text, cast(ObjectiveResult, held[r]),
                                   cast(GradingPolicy, held[p])))
            stopped = replies[-1] is Stopped.OUT_OF_MEMORY
            if stopped or time.monotonic() - began >= GROUP_SECONDS:
                if not _sent(conn, replies) or stopped:
                    return  # the heap may be fragmented near the limit: let the parent start afresh
                replies = []
        if replies and not _readable(conn):  # nothing more to judge now: send them
            if not _sent(conn, replies):
                return
            replies = []


def _sent(conn: Connection, replies: list[Reply]) -> bool:
    """Send ``replies``; False when they could not be (:attr:`Stopped.OUT_OF_MEMORY` is sent
    instead)."""
    try:
        conn.send(replies)
        return True
    except MemoryError:
        conn.send([Stopped.OUT_OF_MEMORY])
        return False


class Sandbox:
    """A reusable worker process that judges answers one at a time, each within bounds.

    Answers travel in batches (one round trip for many answers) and their outcomes in groups;
    each answer still has its own time limit, counted from its own start (from the last
    outcomes received, when those came later). ``judge`` defaults to
    :func:`mechgrade.grade.compare.assess` (tests pass others).

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> acc = ObjectiveResult("a", "scalar", "ft/s^2", 98.51)
    >>> with Sandbox(seconds=10) as box:
    ...     [a.verdict for a in box.assess_many([("98.5 ft/s^2", acc, GradingPolicy()), (None, acc, GradingPolicy())])]
    [<Verdict.CORRECT: 'correct'>, <Verdict.MISSING: 'missing'>]
    """

    def __init__(self, *, seconds: float = DEFAULT_SECONDS, memory_mb: int = DEFAULT_MEMORY_MB,
                 judge: Judge = assess) -> None:
        _check_limits(seconds, memory_mb)
        self.seconds = float(seconds)
        self.memory_mb = memory_mb
        self.judge = judge
        self.restarts = 0
        self._process: BaseProcess | None = None
        self._conn: Connection | None = None
        # the objects the live worker holds: id() -> the object (kept, so its id stays its
        # own) and its number there
        self._held: dict[int, tuple[object, int]] = {}
        self._progress: Progress | None = None
        self.replied = 0  # outcomes received from the live worker

    # -- lifecycle

    def _start(self) -> None:
        _warm()
        methods = multiprocessing.get_all_start_methods()
        context = multiprocessing.get_context("fork" if "fork" in methods else None)
        parent, child = context.Pipe()
        progress = Progress(context)
        process = context.Process(target=_worker,
                                  args=(child, self.judge, self.memory_mb, progress),
                                  daemon=True, name="mechgrade-judge")
        # The worker's collector would walk, and so copy page by page, every object it
        # inherits (sympy's and the solver's): frozen, they are left alone.
        gc.freeze()
        try:
            process.start()
        finally:
            gc.unfreeze()
        child.close()
        self._process, self._conn = process, parent
        self._held, self._progress, self.replied = {}, progress, 0

    def _kill(self) -> None:
        process, conn = self._process, self._conn
        self._process = self._conn = None
        if conn is not None:
            conn.close()
        if process is not None and process.pid is not None and process.is_alive():
            try:
                os.kill(process.pid, signal.SIGKILL)
            except (ProcessLookupError, OSError):
                pass
        if process is not None:
            process.join(5)
        self.restarts += 1

    def close(self) -> None:
        """Stop the worker (politely; killed if it does not stop at once)."""
        process, conn = self._process, self._conn
        if process is None:
            return
        try:
            if conn is not None:
                conn.send(None)
        except (OSError, BrokenPipeError):
            pass
        process.join(1)
        self._kill()
        self.restarts -= 1

    def __enter__(self) -> "Sandbox":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def _send(self, batch: list[Item]) -> bool:
        """Send a batch to a live worker (started or restarted as needed); False if it died."""
        if self._process is None or not self._process.is_alive():
            if self._process is not None:
                self._kill()
            self._start()
        try:
            self.pipe().send(self.message(batch))
            return True
        except (OSError, BrokenPipeError):
            self._kill()
            return False

    def pipe(self) -> Connection:
        """The parent's end of the pipe to the live worker."""
        assert self._conn is not None, "the worker is not running"
        return self._conn

    def progress(self) -> tuple[int, float]:
        """How many answers the live worker has begun, and when it began the last."""
        assert self._progress is not None, "the worker is not running"
        return self._progress.read()

    def message(self, batch: list[Item]) -> Message:
        """``batch`` as it travels to the worker: each reference and policy is sent once per
        worker and then named by its number, so a batch carries little more than its texts
        and the worker judges every answer to an objective against the same object (what it
        works out once per objective is found again by identity)."""
        forget = len(self._held) > MAX_HELD
        if forget:
            self._held = {}
        new: list[tuple[int, object]] = []

        def number(thing: object) -> int:
            known = self._held.get(id(thing))
            if known is None:
                known = self._held[id(thing)] = (thing, len(self._held))
                new.append((known[1], thing))
            return known[1]
        numbered = [(text, number(result), number(policy)) for text, result, policy in batch]
        return forget, new, numbered

    # -- judging

    def assess(self, text: str | None, result: ObjectiveResult,
               policy: GradingPolicy = GradingPolicy()) -> Assessment:
        """Judge one answer; ``not_evaluated`` if it overruns time or memory or crashes."""
        return self.assess_many([(text, result, policy)])[0]

    def assess_many(self, items: Iterable[Item]) -> list[Assessment]:
        """Judge many answers with one worker, in order (a kill restarts it and goes on)."""
        return _judge_spread([self], list(items))


class SandboxPool:
    """Several sandboxes judging one list of answers together: a worker per core.

    Results are in the order of the items, whichever worker judged them, so they do not depend
    on the number of workers.

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> acc = ObjectiveResult("a", "scalar", "ft/s^2", 98.51)
    >>> with SandboxPool(2, seconds=10) as pool:
    ...     [a.verdict for a in pool.assess_many([("98.5 ft/s^2", acc, GradingPolicy()), ("1 m", acc, GradingPolicy())])]
    [<Verdict.CORRECT: 'correct'>, <Verdict.INCORRECT: 'incorrect'>]
    """

    def __init__(self, workers: int, *, seconds: float = DEFAULT_SECONDS,
                 memory_mb: int = DEFAULT_MEMORY_MB, judge: Judge = assess) -> None:
        if not (isinstance(workers, int) and workers > 0):
            raise ValueError(f"expected a positive number of workers, found {workers!r}")
        _check_limits(seconds, memory_mb)
        self.boxes = [Sandbox(seconds=seconds, memory_mb=memory_mb, judge=judge)
                      for _ in range(workers)]

    @property
    def restarts(self) -> int:
        return sum(box.restarts for box in self.boxes)

    def close(self) -> None:
        for box in self.boxes:
            box.close()

    def __enter__(self) -> "SandboxPool":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def assess(self, text: str | None, result: ObjectiveResult,
               policy: GradingPolicy = GradingPolicy()) -> Assessment:
        """Judge one answer (in the first worker)."""
        return self.boxes[0].assess(text, result, policy)

    def assess_many(self, items: Iterable[Item]) -> list[Assessment]:
        """Judge many answers, spread over the workers in small batches, in order."""
        items = list(items)
        boxes = self.boxes[:max(1, min(len(self.boxes), len(items)))]
        return _judge_spread(boxes, items)


def _check_limits(seconds: float, memory_mb: int) -> None:
    if not seconds > 0:
        raise ValueError(f"expected a positive time limit, found {seconds!r}")
    if not (isinstance(memory_mb, int) and memory_mb > 0):
        raise ValueError(f"expected a positive memory limit in MiB, found {memory_mb!r}")


MAX_BATCH = 64


def _judge_spread(boxes: list[Sandbox], items: list[Item]) -> list[Assessment]:
    """Judge ``items`` with ``boxes`` working side by side, each taking the next batch when its
    last one is done; an item repeated in ``items`` is judged once (judging is a function of
    the text, the reference and the policy). Every answer gets ``seconds`` from its start (or
    from its worker's last outcomes received, when later); an overrun, a memory overrun or a
    crash makes that one answer ``not_evaluated``, and the worker is restarted for the rest of
    its batch."""
    try:
        keys = _keys(items)
        first: dict[tuple, int] = {}  # key -> its place among the distinct items
        distinct: list[Item] = []
        for key, item in zip(keys, items):
            if key not in first:
                first[key] = len(distinct)
                distinct.append(item)
    except TypeError:  # an unhashable item (a judge's own argument types): judge every one
        return _judge_each(boxes, items)
    if len(distinct) == len(items):
        return _judge_each(boxes, items)
    judged = _judge_each(boxes, distinct)
    return [judged[first[key]] for key in keys]


def _keys(items: list[Item]) -> list[tuple]:
    """Keys that are equal exactly when the items are, hashing each distinct object once
    (hashing a reference with its mistakes costs more than a worker's round trip)."""
    same: dict[int, int] = {}  # id of an object -> id of the first equal one
    seen: dict[object, int] = {}

    def representative(thing: object) -> int:
        if id(thing) not in same:
            same[id(thing)] = seen.setdefault(thing, id(thing))
        return same[id(thing)]
    return [(text, representative(result), representative(policy))
            for text, result, policy in items]


def _judge_each(boxes: list[Sandbox], items: list[Item]) -> list[Assessment]:
    return _Spread(boxes, items).run()


def _readable(conn: Connection) -> bool:
    """Whether ``conn`` has something to read now: one ``select`` (``conn.poll`` builds a
    selector each time, which costs more than receiving an outcome)."""
    return bool(select.select([conn], [], [], 0)[0])


class _Spread:
    """One list of answers judged by workers side by side (:func:`_judge_spread`)."""

    def __init__(self, boxes: list[Sandbox], items: list[Item]) -> None:
        self.boxes = boxes
        self.items = items
        self.results: list[Assessment | None] = [None] * len(items)
        self.sent = 0  # items[:sent] have gone to a worker
        # the answers each worker has been sent and not answered, in order; a worker holds up
        # to two batches, so it starts the next as soon as it finishes one
        self.pending: dict[Sandbox, deque[int]] = {}
        self.deadline: dict[Sandbox, float] = {}  # seconds after its last outcomes came
        self.began = time.monotonic()
        self.answered = 0

    def batch_size(self) -> int:
        """A quarter of each worker's share of what is left (at most :data:`MAX_BATCH`):
        batches shrink towards the end, so the workers finish together."""
        return max(1, min(MAX_BATCH, (len(self.items) - self.sent) // (4 * len(self.boxes))))

    def send(self, box: Sandbox, indices: deque[int]) -> None:
        """Hand ``indices`` to ``box``; an answer the worker cannot even receive is not judged."""
        if self.pending.get(box):
            # Answers are in flight: the worker is never restarted under them. If it has died,
            # its end of file is read as usual and these go to the fresh worker with the rest.
            try:
                box.pipe().send(box.message([self.items[i] for i in indices]))
            except OSError:
                pass
            self.pending[box] += indices
            return
        while indices:
            if box._send([self.items[i] for i in indices]):
                self.pending[box] = indices
                self.deadline[box] = time.monotonic() + box.seconds
                return
            self.results[indices.popleft()] = not_evaluated("the judging process stopped", None)

    def per_answer(self) -> float | None:
        """Seconds per answer of one worker so far (``None`` before the first outcome)."""
        if not self.answered:
            return None
        return (time.monotonic() - self.began) * len(self.boxes) / self.answered

    def refill(self, box: Sandbox) -> None:
        """Keep ``box`` holding a batch beyond the one it is judging, and at least four
        groups' worth of answers (:data:`GROUP_SECONDS`), while answers remain."""
        per_answer = self.per_answer()
        hold = self.batch_size() if per_answer is None else max(
            self.batch_size(), min(4 * MAX_BATCH, int(4 * GROUP_SECONDS / per_answer)))
        start, held = self.sent, len(self.pending.get(box, ()))
        while self.sent < len(self.items) and held + self.sent - start <= hold:
            self.sent += self.batch_size()
        if self.sent > start:  # the batches in one message
            self.send(box, deque(range(start, self.sent)))
        if box in self.pending and not self.pending[box]:
            del self.pending[box]

    def due(self, box: Sandbox, began: float) -> float:
        """When ``box`` overruns: ``seconds`` after the answer it is judging ``began``, or
        after its last outcomes came, whichever is later."""
        return max(self.deadline[box], began + box.seconds)

    def fail(self, box: Sandbox, assessment: Assessment, begun: int | None = None) -> None:
        """The answer ``box`` was judging gets ``assessment``: its ``begun``-th (default: the
        last it began; the first it holds, when it had begun none of them). The others,
        judged or not, go to a fresh worker."""
        indices = self.pending.pop(box)
        begun = box.progress()[0] if begun is None else begun
        current = min(max(begun - box.replied - 1, 0), len(indices) - 1)
        self.results[indices[current]] = assessment
        del indices[current]
        box._kill()
        self.send(box, indices)
        self.refill(box)

    def receive(self, box: Sandbox) -> None:
        """Read every outcome ``box`` has sent so far."""
        conn = box.pipe()
        while True:
            try:
                replies: list[Reply] = conn.recv()
            except (EOFError, OSError):
                self.fail(box, not_evaluated("the judging process stopped (out of memory?)"))
                return
            for reply in replies:
                if reply is Stopped.OUT_OF_MEMORY:
                    self.fail(box, not_evaluated(f"judging needed more than {box.memory_mb} MiB"))
                    return
                self.results[self.pending[box].popleft()] = reply
                box.replied += 1
            self.answered += len(replies)
            self.deadline[box] = time.monotonic() + box.seconds
            self.refill(box)  # may start a fresh worker, when this one died after its outcome
            if box not in self.pending or conn is not box._conn or not _readable(conn):
                return

    def run(self) -> list[Assessment]:
        for box in self.boxes:
            self.refill(box)
        while self.pending:
            wait_for = max(0.0, min(self.due(box, box.progress()[1]) for box in self.pending)
                           - time.monotonic())
            try:
                # one select (connection.wait builds a selector each time: 14 us, 4 here)
                ready = select.select([box.pipe() for box in self.pending], [], [], wait_for)[0]
            except OSError:
                ready = []
            answered = [box for box in self.pending if box._conn in ready]
            for box in answered:
                self.receive(box)
            now = time.monotonic()
            for box in [b for b in self.pending if b not in answered]:
                begun, began = box.progress()  # the answer that overran, even if it ends now
                if self.due(box, began) <= now:
                    self.fail(box, not_evaluated(f"judging took longer than {box.seconds:g} s"),
                              begun)
        assert all(result is not None for result in self.results)
        return cast(list[Assessment], self.results)


def assess_bounded(text: str | None, result: ObjectiveResult, policy: GradingPolicy = GradingPolicy(), *,
                   seconds: float = DEFAULT_SECONDS,
                   memory_mb: int = DEFAULT_MEMORY_MB) -> Assessment:
    """Judge one answer in a fresh worker (for many answers use :func:`assess_batch`)."""
    with Sandbox(seconds=seconds, memory_mb=memory_mb) as box:
        return box.assess(text, result, policy)


def assess_batch(items: Sequence[Item] | Iterable[Item], *, seconds: float = DEFAULT_SECONDS,
                 memory_mb: int = DEFAULT_MEMORY_MB) -> list[Assessment]:
    """Judge many answers in one reused worker, each within ``seconds`` and ``memory_mb``
    (the answers travel to the worker in batches).

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> acc = ObjectiveResult("a", "scalar", "ft/s^2", 98.51)
    >>> [a.verdict for a in assess_batch([("98.5 ft/s^2", acc, GradingPolicy()), ("1 m", acc, GradingPolicy())])]
    [<Verdict.CORRECT: 'correct'>, <Verdict.INCORRECT: 'incorrect'>]
    """
    with Sandbox(seconds=seconds, memory_mb=memory_mb) as box:
        return box.assess_many(items)
