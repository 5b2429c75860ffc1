"""Progress of long work: a bar with an ETA on a terminal, a periodic status line elsewhere.

One helper for every long loop (speed scans, studies, design searches, transients)::

    from gfbopt.progress import progress

    with progress(total=len(speeds), desc="onset scan", unit="speed") as bar:
        for speed in speeds:
            ...
            bar.update(1)

* stderr is a terminal: a ``tqdm`` bar with rate and ETA (tqdm is a maintained library; no
  hand-drawn bar);
* stderr is not a terminal (CI, a log file, ``nohup``): one line to stderr at most every
  ``interval_s`` seconds (default 10 s) — ``gfbopt: onset scan 12/40 speed (30 %), 8.1 s,
  ETA 19 s`` — and one final line when the work ends, so a log shows the run is alive;
* ``enabled=False`` (or ``GFBOPT_PROGRESS=0`` in the environment): silent.

A run of several stages reports one fraction through :class:`Stages`: each stage is weighed
by the work it will do (its evaluations or solves, the cost of one against the others, and
how many run at once), so the bar and its ETA count every stage, not the first one only.

Progress goes to stderr only, so ``--json`` on stdout stays machine-readable.  Nothing here is
module-level state: each ``progress(...)`` is its own object.
"""
from __future__ import annotations

import math
import os
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import IO, Optional

#: seconds between two status lines when stderr is not a terminal
DEFAULT_INTERVAL_S = 10.0


def _format_seconds(seconds: float) -> str:
    if seconds < 60:
        return f"{seconds:.1f} s"
    minutes, sec = divmod(int(round(seconds)), 60)
    if minutes < 60:
        return f"{minutes} min {sec:02d} s"
    hours, minutes = divmod(minutes, 60)
    return f"{hours} h {minutes:02d} min"


class StatusLine:
    """Periodic one-line status for a stream that is not a terminal (same API as a tqdm bar:
    ``update``, ``set_postfix_str``, ``close``, context manager)."""

    def __init__(self, total: Optional[int], desc: str, unit: str, stream: IO[str],
                 interval_s: float = DEFAULT_INTERVAL_S, clock=time.monotonic) -> None:
        self.total = total
        self.desc = desc
        self.unit = unit
        self.stream = stream
        self.interval_s = interval_s
        self._clock = clock
        self._start = clock()
        self._last = self._start
        self.n = 0
        self._postfix = ""
        self._closed = False

    def line(self) -> str:
        """The status line for the current count (what is written)."""
        elapsed = self._clock() - self._start
        if self.total and self.unit == "%" and self.total == 100:    # a fraction of a run
            text = f"gfbopt: {self.desc} {self.n} %, {_format_seconds(elapsed)}"
        elif self.total:
            fraction = self.n / self.total
            text = (f"gfbopt: {self.desc} {self.n}/{self.total} {self.unit} "
                    f"({100.0 * fraction:.0f} %), {_format_seconds(elapsed)}")
        else:
            text = f"gfbopt: {self.desc} {self.n} {self.unit}, {_format_seconds(elapsed)}"
        if self.total and 0 < self.n < self.total:
            eta = elapsed * (self.total - self.n) / self.n
            text += f", ETA {_format_seconds(eta)}"
        if self._postfix:
            text += f" [{self._postfix}]"
        return text

    def _emit(self) -> None:
        print(self.line(), file=self.stream, flush=True)
        self._last = self._clock()

    def update(self, n: int = 1) -> None:
        self.n += n
        if self._clock() - self._last >= self.interval_s:
            self._emit()

    def set_postfix_str(self, text: str) -> None:
        self._postfix = text

    def close(self) -> None:
        if not self._closed:
            self._closed = True
            self._emit()

    def __enter__(self) -> "StatusLine":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class _Silent:
    """No output (progress disabled); the same API."""

    n = 0

    def update(self, n: int = 1) -> None:
        self.n += n

    def set_postfix_str(self, text: str) -> None:
        pass

    def close(self) -> None:
        pass

    def __enter__(self) -> "_Silent":
        return self

    def __exit__(self, *exc) -> None:
        pass


def progress(total: Optional[int] = None, desc: str = "working", unit: str = "step", *,
             enabled: bool = True, stream: Optional[IO[str]] = None,
             interval_s: float = DEFAULT_INTERVAL_S):
    """A progress reporter for ``total`` units of work (None: unknown total).

    A tqdm bar with an ETA when ``stream`` (default stderr) is a terminal, a
    :class:`StatusLine` otherwise, silent when ``enabled`` is false or the environment sets
    ``GFBOPT_PROGRESS=0``.  Use as a context manager and call ``update(n)``.
    """
    stream = sys.stderr if stream is None else stream
    if not enabled or os.environ.get("GFBOPT_PROGRESS", "1") == "0":
        return _Silent()
    isatty = getattr(stream, "isatty", None)
    if isatty is not None and isatty():
        from tqdm import tqdm

        return tqdm(total=total, desc=f"gfbopt: {desc}", unit=f" {unit}", file=stream,
                    dynamic_ncols=True, leave=True)
    return StatusLine(total, desc, unit, stream, interval_s=interval_s)


@dataclass(frozen=True)
class Stage:
    """One stage of a run: ``tasks`` evaluations or solves of ``cost`` each (in any unit
    shared by the run's stages), ``slots`` of them at once (the workers)."""

    name: str
    tasks: int
    cost: float = 1.0
    slots: int = 1

    @property
    def work(self) -> float:
        """Wall-time units of the stage: rounds of ``slots`` tasks times the cost of one."""
        if self.tasks <= 0:
            return 0.0
        return math.ceil(self.tasks / max(1, min(self.slots, self.tasks))) * self.cost


class Fraction:
    """A reporter with the API of :func:`progress` (``update``, ``set_postfix_str``,
    ``close``) that passes the fraction of ``total`` done to ``report`` — for a solver that
    counts its own units (revolutions of an orbit) inside one stage of a run."""

    def __init__(self, total: float, report: Callable[[float], None]) -> None:
        self.total, self.report, self.n = total, report, 0

    def update(self, n: int = 1) -> None:
        self.n += n
        self.report(min(1.0, self.n / self.total) if self.total else 1.0)

    def set_postfix_str(self, text: str) -> None:
        pass

    def close(self) -> None:
        pass


class Stages:
    """One fraction of a whole run from the progress of its stages (:class:`Stage`).

    ``stage(name)`` starts a stage and returns its callback (the fraction of its own work
    done); starting the next stage, or :meth:`finish`, closes it.  The run's fraction is the
    work done over the work done plus the work still planned, so a stage that ends early
    (an orbit that stops at contact) or is skipped counts only the work it did: the bar
    moves ahead and the ETA (elapsed × remaining / done) is re-based on the work left,
    never on work that will not be done.  A stage that does its work without reporting
    must call its callback with 1.0 when it ends.  ``None`` as ``report``: silent."""

    def __init__(self, report: Optional[Callable[[float], None]], stages: Sequence[Stage]):
        names = [s.name for s in stages]
        if len(set(names)) != len(names):
            raise ValueError(f"stage names must differ: {names}")
        self.report = report
        self.stages = tuple(stages)
        self.done = 0.0                 # work of the closed stages, as they did it
        self.current: Optional[int] = None
        self.current_fraction = 0.0
        self.fraction = 0.0

    def _index(self, name: str) -> int:
        for k, s in enumerate(self.stages):
            if s.name == name:
                return k
        raise KeyError(f"no stage {name!r} (stages: {', '.join(s.name for s in self.stages)})")

    def _close(self) -> None:
        if self.current is not None:
            self.done += self.stages[self.current].work * self.current_fraction
        self.current, self.current_fraction = None, 0.0

    def _emit(self) -> None:
        k = self.current                # a stage is running
        now = self.stages[k].work * self.current_fraction
        total = self.done + sum(s.work for s in self.stages[k:])    # skipped ones: none
        fraction = (self.done + now) / total if total > 0 else 0.0
        self.fraction = max(self.fraction, min(1.0, fraction))
        if self.report is not None:
            self.report(self.fraction)

    def stage(self, name: str) -> Callable[[float], None]:
        """Start stage ``name`` (the stages before it not started are skipped: no work);
        returns its callback, to be called with the fraction of its work done."""
        k = self._index(name)
        if self.current is not None and k <= self.current:
            raise ValueError(f"stage {name!r} is not after {self.stages[self.current].name!r}")
        self._close()
        self.current = k
        self._emit()

        def step(fraction: float) -> None:
            if self.current == k:
                self.current_fraction = max(self.current_fraction,
                                            min(1.0, max(0.0, float(fraction))))
                self._emit()
        return step

    def finish(self) -> None:
        """The run is done (the stages not started were skipped)."""
        self._close()
        self.fraction = 1.0
        if self.report is not None:
            self.report(1.0)
