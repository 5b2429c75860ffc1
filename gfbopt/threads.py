"""One BLAS/OpenMP thread inside gfbopt's solver calls, whoever calls them.

gfbopt's linear algebra is many small factorisations and solves: sparse LUs of a few thousand
unknowns, triangular solves and eigenvalues of matrices of order 4–60.  Multi-threaded
OpenBLAS (numpy's and scipy's each bring one) hands each such call to a pool of threads that
then spin waiting for the next: on the 2-core test machine the rotor analysis of
``problems/rotors/blower.toml`` at 36x10 takes 3–4× the CPU time with two BLAS threads as
with one, nearly all of it in the order-≤60 triangular solves of
:mod:`gfbopt.rotor.reduced` and in :func:`numpy.linalg.eigvals` of the matched-whirl
pencils (benchmarks/bench_api_threads.py).  The answers are the same bits either way.

:func:`single_threaded` (a decorator) and :func:`solver_threads` (a context) limit every BLAS
and OpenMP library threadpoolctl sees to one thread for the duration of the outermost gfbopt
call and give each library back its own count on exit, so a program that calls gfbopt keeps
the thread settings it had around the call (and between calls).  Nested calls cost a context
variable look-up: the limit is applied once per outermost call.  A user who has set one of
:data:`THREAD_VARIABLES` keeps that choice: nothing is changed then, as on the command line.

:func:`pin_threads` sets the limit for the rest of a process gfbopt owns: the command line
(unless the user set a thread variable) and the pool workers (always).

The thread counts of the libraries belong to the process, so does the bookkeeping here: the
first of several threads that enter gfbopt applies the limit, the last to leave restores it.
The limit uses threadpoolctl's cached controller (1–2 ms to build: it lists the loaded
libraries; built again only when modules have been imported since), so entering an
outermost call costs ~30 µs.
"""
from __future__ import annotations

import contextlib
import contextvars
import functools
import os
import threading
from collections.abc import Callable, Iterator
from typing import TypeVar

#: environment variables by which a user chooses the BLAS/OpenMP thread count (kept when set)
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")

#: whether this context is inside a gfbopt call that holds (or has decided on) the limit
_INSIDE: contextvars.ContextVar = contextvars.ContextVar("gfbopt_solver_threads",
                                                         default=False)

F = TypeVar("F", bound=Callable)


def user_set_threads() -> bool:
    """True when the user chose a thread count with one of :data:`THREAD_VARIABLES`."""
    return any(os.environ.get(name) for name in THREAD_VARIABLES)


def _controller():
    """threadpoolctl's controller of the libraries loaded now: its cached one (rebuilt when
    modules have been imported since), a new one on threadpoolctl < 3.6."""
    import threadpoolctl

    cached = getattr(threadpoolctl, "get_cached_controller", None)
    return cached() if cached is not None else threadpoolctl.ThreadpoolController()


def _release_openblas_control() -> None:
    """Let any thread set OpenBLAS's process-wide count again (threadpoolctl >= 3.6 gives
    that right to one thread at a time, the one that set it last)."""
    from threadpoolctl import OpenBLASController

    clear = getattr(OpenBLASController, "clear_controlling_thread", None)
    if clear is not None:
        clear(force=True)


class _ProcessLimit:
    """The one-thread limit of this process, held while any thread is inside gfbopt."""

    def __init__(self):
        self._lock = threading.Lock()
        self._holders = 0
        self._limiter = None

    def acquire(self) -> None:
        with self._lock:
            if self._holders == 0:
                _release_openblas_control()      # a user's thread may hold it
                self._limiter = _controller().limit(limits=1)
            self._holders += 1

    def release(self) -> None:
        with self._lock:
            self._holders -= 1
            if self._holders == 0:
                limiter, self._limiter = self._limiter, None
                _release_openblas_control()      # the last to leave may not be the first in
                limiter.restore_original_limits()
                _release_openblas_control()      # as ``with threadpool_limits()`` leaves it

    def pin(self) -> None:
        """One thread from now on (not restored)."""
        with self._lock:
            _controller().limit(limits=1)


_PROCESS = _ProcessLimit()


@contextlib.contextmanager
def solver_threads() -> Iterator[None]:
    """One BLAS/OpenMP thread inside the block, each library's own count restored after it
    (module docstring); nothing changed when the user set a thread variable or when an
    enclosing gfbopt call holds the limit already."""
    if _INSIDE.get():
        yield
        return
    token = _INSIDE.set(True)
    try:
        limit = not user_set_threads()
        if limit:
            _PROCESS.acquire()
        try:
            yield
        finally:
            if limit:
                _PROCESS.release()
    finally:
        _INSIDE.reset(token)


def single_threaded(function: F) -> F:
    """``function`` run inside :func:`solver_threads` (free when called from inside one)."""
    @functools.wraps(function)
    def call(*args, **kwargs):
        if _INSIDE.get():
            return function(*args, **kwargs)
        with solver_threads():
            return function(*args, **kwargs)

    return call  # type: ignore[return-value]


def pin_threads(keep_user_choice: bool = True) -> None:
    """One BLAS/OpenMP thread for the rest of this process (not restored): the command line
    keeps a user's :data:`THREAD_VARIABLES`; the pool workers pin whatever they say
    (``keep_user_choice=False``)."""
    if keep_user_choice and user_set_threads():
        return
    _PROCESS.pin()
