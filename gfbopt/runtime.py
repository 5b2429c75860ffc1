"""What can stop a run that is not a result of its points: a signal, a lost worker, a lost
cluster.  Shared by the local executors (:mod:`gfbopt.parallel`) and the Dask one
(:mod:`gfbopt.cluster`)."""
from __future__ import annotations

import contextlib
import contextvars
import signal
import threading
from collections.abc import Callable


class InfrastructureFailure(RuntimeError):
    """A task that could not be run because its workers kept dying or the cluster was lost:
    not a result of its points (a resume computes them)."""


class InfrastructureError(RuntimeError):
    """The executor itself is gone (a lost Dask scheduler, no worker left): the run stops;
    what finished is stored and a resume computes the rest."""


class Interrupted(KeyboardInterrupt):
    """SIGTERM or SIGINT received (``signum``); ``report`` says what was kept."""

    def __init__(self, signum: int, report: str = ""):
        self.signum = signum
        self.report = report
        super().__init__(report or signal.Signals(signum).name)

    @property
    def exit_status(self) -> int:
        """128 + the signal number: 143 for SIGTERM, 130 for SIGINT."""
        return 128 + int(self.signum)


class SignalState:
    """The signal received inside :func:`interrupt_on_signals` (None until one arrives)."""

    def __init__(self) -> None:
        self.received = None

    def check(self) -> None:
        if self.received is not None:
            raise Interrupted(self.received)


_SIGNALS: contextvars.ContextVar = contextvars.ContextVar("gfbopt_signals", default=None)


def check_interrupted() -> None:
    """Raise :class:`Interrupted` if SIGTERM/SIGINT arrived inside
    :func:`interrupt_on_signals`.  Called at safe points (after each point), because a
    native solver may swallow the exception the signal handler raised: CasADi turns a
    Python exception raised during an IPOPT solve into a failed solve
    ("KeyboardInterruptException") and carries on."""
    state = _SIGNALS.get()
    if state is not None:
        state.check()


def forget_signals() -> None:
    """In a forked worker: drop the signal state inherited from the driver (the driver
    handles the signals; the worker ignores them)."""
    _SIGNALS.set(None)


def interrupted() -> bool:
    """True once SIGTERM/SIGINT arrived inside :func:`interrupt_on_signals`."""
    state = _SIGNALS.get()
    return state is not None and state.received is not None


@contextlib.contextmanager
def interrupt_on_signals():
    """Within the block, SIGTERM (what ``timeout``, systemd, SLURM and Kubernetes send) and
    SIGINT raise :class:`Interrupted` in the main thread — at once, and again at the next
    safe point (:func:`check_interrupted`) if native code swallowed it — so ``finally``
    blocks run (the results buffer is written) instead of the process dying with unwritten
    rows.  Nested blocks share the outer one; outside the main thread it does nothing.
    The previous handlers are restored on exit."""
    if threading.current_thread() is not threading.main_thread() or \
            _SIGNALS.get() is not None:
        yield _SIGNALS.get()
        return
    state = SignalState()

    def handler(signum, frame):
        state.received = signum
        raise Interrupted(signum)

    previous = {s: signal.signal(s, handler) for s in (signal.SIGTERM, signal.SIGINT)}
    token = _SIGNALS.set(state)
    try:
        yield state
    finally:
        _SIGNALS.reset(token)
        for s, h in previous.items():
            signal.signal(s, h)


def call_task(function: Callable, argument):
    """Run one task in a worker; an exception is returned (as data), never raised."""
    try:
        return function(argument)
    except Exception as exc:  # noqa: BLE001 - a failed task is rows with its error
        return exc


