"""Judge answers in a worker process with a memory limit and a wall-clock kill.

sympy can hang in C-level loops or huge integer arithmetic (``9**9**9``, ``factorial(10**9)``,
``simplify`` of ``(x+1)**3000``, even ``str()`` of some results) and no thread timeout can stop
that. So answers are judged in a worker process, forked after sympy and the unit registry are
imported (the fork inherits them, so starting a worker costs milliseconds, not seconds). The
worker limits its address space (``RLIMIT_AS``); the parent waits at most ``seconds`` per answer
and kills the worker on overrun. An overrun gives the verdict ``not_evaluated`` ("could not be
evaluated", never "wrong") and the run goes on with a fresh worker; a worker is reused for many
answers and replaced only after a kill or a crash.

>>> from mechgrade.solve.result import ObjectiveResult
>>> acc = ObjectiveResult("a", "scalar", "ft/s^2", 98.51)
>>> assess_bounded("98.5 ft/s^2", acc, Policy(), seconds=10, memory_mb=512).verdict
'correct'
"""

from __future__ import annotations

import multiprocessing
import os
import signal
from typing import Callable, Iterable, Sequence

from ..solve.result import ObjectiveResult
from .compare import Assessment, Policy, assess, not_evaluated

Judge = Callable[[str | None, ObjectiveResult, Policy], Assessment]
Item = tuple[str | None, ObjectiveResult, Policy]

DEFAULT_SECONDS = 5.0
DEFAULT_MEMORY_MB = 512


def _warm() -> None:
    """Import what judging needs before forking, so every worker inherits it."""
    import sympy  # noqa: F401

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
        soft, hard = resource.getrlimit(resource.RLIMIT_AS)
        if hard != resource.RLIM_INFINITY:
            limit = min(limit, hard)
        resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    except (ValueError, OSError):  # pragma: no cover - the limit could not be lowered
        pass


def _worker(conn, judge: Judge, memory_mb: int) -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent decides when we stop
    _limit_memory(memory_mb)
    while True:
        try:
            item = conn.recv()
        except (EOFError, OSError):
            return
        if item is None:
            return
        text, result, policy = item
        try:
            outcome = ("ok", judge(text, result, policy))
        except MemoryError:
            outcome = ("memory", None)
        except RecursionError:
            outcome = ("error", "the expression is nested too deeply to evaluate")
        except Exception as exc:  # noqa: BLE001 - any failure is "could not be evaluated"
            outcome = ("error", f"{type(exc).__name__} while judging")
        try:
            conn.send(outcome)
        except MemoryError:
            conn.send(("memory", None))
        if outcome[0] == "memory":
            return  # the heap may be fragmented near the limit: let the parent start afresh


class Sandbox:
    """A reusable worker process that judges answers one at a time, each within bounds.

    ``judge`` defaults to :func:`mechgrade.grade.compare.assess` (tests pass others).

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> acc = ObjectiveResult("a", "scalar", "ft/s^2", 98.51)
    >>> with Sandbox(seconds=10) as box:
    ...     [a.verdict for a in box.assess_many([("98.5 ft/s^2", acc, Policy()), (None, acc, Policy())])]
    ['correct', 'missing']
    """

    def __init__(self, *, seconds: float = DEFAULT_SECONDS, memory_mb: int = DEFAULT_MEMORY_MB,
                 judge: Judge = assess) -> None:
        if not seconds > 0:
            raise ValueError(f"expected a positive time limit, found {seconds!r}")
        if not (isinstance(memory_mb, int) and memory_mb > 0):
            raise ValueError(f"expected a positive memory limit in MiB, found {memory_mb!r}")
        self.seconds = float(seconds)
        self.memory_mb = memory_mb
        self.judge = judge
        self.restarts = 0
        self._process = None
        self._conn = None

    # -- lifecycle

    def _start(self) -> None:
        _warm()
        methods = multiprocessing.get_all_start_methods()
        context = multiprocessing.get_context("fork" if "fork" in methods else None)
        parent, child = context.Pipe()
        process = context.Process(target=_worker, args=(child, self.judge, self.memory_mb),
                                  daemon=True, name="mechgrade-judge")
        process.start()
        child.close()
        self._process, self._conn = process, parent

    def _kill(self) -> None:
        process, conn = self._process, self._conn
        self._process = self._conn = None
        if conn is not None:
            conn.close()
        if process is not None and process.is_alive():
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

    # -- judging

    def assess(self, text: str | None, result: ObjectiveResult,
               policy: Policy = Policy()) -> Assessment:
        """Judge one answer; ``not_evaluated`` if it overruns time or memory or crashes."""
        if self._process is None or not self._process.is_alive():
            if self._process is not None:
                self._kill()
            self._start()
        try:
            self._conn.send((text, result, policy))
        except (OSError, BrokenPipeError):
            self._kill()
            return not_evaluated("the judging process stopped", None)
        try:
            ready = self._conn.poll(self.seconds)
        except (OSError, EOFError):
            ready = False
        if not ready:
            self._kill()
            return not_evaluated(f"judging took longer than {self.seconds:g} s")
        try:
            status, payload = self._conn.recv()
        except (EOFError, OSError):
            self._kill()
            return not_evaluated("the judging process stopped (out of memory?)")
        if status == "ok":
            return payload
        if status == "memory":
            self._kill()
            return not_evaluated(f"judging needed more than {self.memory_mb} MiB")
        return not_evaluated(payload)

    def assess_many(self, items: Iterable[Item]) -> list[Assessment]:
        """Judge many answers with one worker, in order (a kill restarts it and goes on)."""
        return [self.assess(text, result, policy) for text, result, policy in items]


def assess_bounded(text: str | None, result: ObjectiveResult, policy: Policy = Policy(), *,
                   seconds: float = DEFAULT_SECONDS,
                   memory_mb: int = DEFAULT_MEMORY_MB) -> Assessment:
    """Judge one answer in a fresh worker (for many answers use :func:`assess_batch`)."""
    with Sandbox(seconds=seconds, memory_mb=memory_mb) as box:
        return box.assess(text, result, policy)


def assess_batch(items: Sequence[Item] | Iterable[Item], *, seconds: float = DEFAULT_SECONDS,
                 memory_mb: int = DEFAULT_MEMORY_MB) -> list[Assessment]:
    """Judge many answers in one reused worker, each within ``seconds`` and ``memory_mb``.

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> acc = ObjectiveResult("a", "scalar", "ft/s^2", 98.51)
    >>> [a.verdict for a in assess_batch([("98.5 ft/s^2", acc, Policy()), ("1 m", acc, Policy())])]
    ['correct', 'incorrect']
    """
    with Sandbox(seconds=seconds, memory_mb=memory_mb) as box:
        return box.assess_many(items)
