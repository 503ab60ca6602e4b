"""Work spread over the machine's cores in forked processes.

A forked worker inherits everything the parent has loaded (sympy, the unit registry, a grade
report), so starting one costs milliseconds. Results come back in the order of the work, so
they never depend on the number of workers.

Every worker dies with the process that forked it, even one killed with ``SIGKILL`` (as the
out-of-memory killer does, which leaves no clean-up code a chance to run), and never holds the
terminal's output open (:func:`worker_started`).

>>> fork_map(abs, [-1, 2, -3], jobs=2)
[1, 2, 3]
"""

from __future__ import annotations

import ctypes
import multiprocessing
import os
import signal
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import TYPE_CHECKING, Callable, Generic, Iterable, TypeVar

from .errors import MechgradeError

if TYPE_CHECKING:
    from multiprocessing.connection import Connection
    from multiprocessing.process import BaseProcess

T = TypeVar("T")
R = TypeVar("R")


def default_jobs() -> int:
    """The number of cores this process may run on (at least 1).

    >>> default_jobs() >= 1
    True
    """
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):  # pragma: no cover - not on Linux
        return max(1, os.cpu_count() or 1)


def fork_map(func: Callable[[T], R], items: Iterable[T], *, jobs: int) -> list[R]:
    """``[func(item) for item in items]``, in up to ``jobs`` forked processes.

    The items go to the workers in a few chunks per worker (a round trip per item would cost
    more than reading a small file). ``func`` and the items' results must pickle; an exception
    raised by ``func`` is raised here as in a plain loop. Without ``fork`` (or with ``jobs`` 1,
    or one item) the work runs in this process; so does a chunk whose worker died.
    """
    items = list(items)
    if jobs <= 1 or len(items) <= 1 or "fork" not in multiprocessing.get_all_start_methods():
        return [func(item) for item in items]
    pieces = min(len(items), 4 * jobs)
    chunks = [items[len(items) * i // pieces:len(items) * (i + 1) // pieces]
              for i in range(pieces)]
    context = multiprocessing.get_context("fork")
    results: list[R] = []
    with ProcessPoolExecutor(max_workers=min(jobs, pieces), mp_context=context,
                             initializer=worker_started) as pool:
        futures = [pool.submit(_map_chunk, func, chunk) for chunk in chunks]
        for chunk, future in zip(chunks, futures):
            try:
                results.extend(future.result())
            except BrokenProcessPool:  # a worker was killed (out of memory?): do it here
                results.extend(_map_chunk(func, chunk))
    return results


def _map_chunk(func: Callable[[T], R], chunk: list[T]) -> list[R]:
    return [func(item) for item in chunk]


class Forked(Generic[R]):
    """``work()`` running in a forked process from now on; :meth:`result` waits for its value.

    For work that needs little of what the parent still has to load (reading submissions while
    the parent imports the solver). Without ``fork``, or when the process fails or dies, the
    work is done here when the result is asked for (so its own exception is raised here).

    >>> Forked(lambda: 6 * 7).result()
    42
    """

    def __init__(self, work: Callable[[], R]) -> None:
        self._work = work
        self._process: BaseProcess | None = None
        self._conn: Connection | None = None
        if "fork" in multiprocessing.get_all_start_methods():
            context = multiprocessing.get_context("fork")
            self._conn, child = context.Pipe(duplex=False)
            self._process = context.Process(target=_send_outcome, args=(child, work),
                                            daemon=False, name="mechgrade-forked")
            self._process.start()
            child.close()

    def result(self) -> R:
        if self._process is None or self._conn is None:
            return self._work()
        try:
            done, value = self._conn.recv()
        except (EOFError, OSError):
            done, value = False, None
        finally:
            self.cancel()
        return value if done else self._work()

    def cancel(self) -> None:
        """Stop the process (if it still runs) and forget it."""
        process, conn = self._process, self._conn
        if conn is not None:
            conn.close()
        if process is not None:
            if process.is_alive():
                process.kill()
            process.join()


def _send_outcome(conn, work: Callable[[], R]) -> None:
    worker_started()
    message: tuple[bool, object]  # whether the work was done, and its value
    try:
        message = (True, work())
    except Exception:  # noqa: BLE001 - the parent does the work again and sees the error
        message = (False, None)
    try:
        conn.send(message)
    except Exception:  # noqa: BLE001 - e.g. a value that does not pickle: same as above
        conn.send((False, None))


PR_SET_PDEATHSIG = 1  # from <linux/prctl.h>
WATCH_SECONDS = 0.5


def worker_started() -> None:
    """Bind a forked worker (call it first thing in the worker) to the process that forked it.

    * It is killed as soon as that process dies, however it dies: Linux sends it ``SIGKILL``
      then (``prctl(PR_SET_PDEATHSIG)``); elsewhere a watchdog thread sees its parent change.
      A worker otherwise outlives a parent killed with ``SIGKILL``, blocked for ever on a pipe
      that its sibling workers keep open.
    * Its standard output and error go to ``/dev/null``: a worker that outlived its parent even
      for a moment would keep the terminal's pipe open (``mechgrade grade | tee log`` would not
      end), and nothing a worker says is meant for the user (results travel through pipes).

    Outside a process started by :mod:`multiprocessing` it does nothing.

    >>> worker_started()  # in the main process: nothing to bind to
    """
    parent = multiprocessing.parent_process()
    if parent is None or parent.pid is None:
        return
    watched = not _die_with_parent()
    if os.getppid() != parent.pid:  # the parent died before the line above took effect
        os._exit(1)
    if watched:
        threading.Thread(target=_watch_parent, args=(parent.pid,), daemon=True,
                         name="mechgrade-parent-watch").start()
    _away_from_the_terminal()


def _die_with_parent() -> bool:
    """Ask Linux to kill this process when its parent dies; whether it was done."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) == 0
    except (OSError, AttributeError):  # pragma: no cover - no usable C library
        return False


def _watch_parent(parent: int) -> None:  # pragma: no cover - used where Linux's is missing
    while os.getppid() == parent:
        time.sleep(WATCH_SECONDS)
    os._exit(1)


def _away_from_the_terminal() -> None:
    try:
        null = os.open(os.devnull, os.O_RDWR)
    except OSError:  # pragma: no cover - no /dev/null: keep the streams as they are
        return
    for fd in (1, 2):
        try:
            os.dup2(null, fd)
        except OSError:  # pragma: no cover - a stream closed already
            pass
    os.close(null)


def outcome(work: Callable[[], R]) -> R | MechgradeError:
    """``work()``, or the :class:`MechgradeError` it raised: for :func:`fork_map`, so that errors
    are raised in the order of the work, whichever process met one first.

    >>> outcome(lambda: 1), str(outcome(lambda: raise_first([MechgradeError("bad")])))
    (1, 'bad')
    """
    try:
        return work()
    except MechgradeError as err:
        return err


def raise_first(outcomes: list) -> list:
    """``outcomes`` (of :func:`outcome`), unless one is an error: then the first is raised."""
    for item in outcomes:
        if isinstance(item, MechgradeError):
            raise item
    return outcomes
