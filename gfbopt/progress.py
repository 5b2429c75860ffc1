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

Progress goes to stderr only, so ``--json`` on stdout stays machine-readable.  Nothing here is
module-level state: each ``progress(...)`` is its own object.
"""
from __future__ import annotations

import os
import sys
import time
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
        if self.total:
            fraction = self.n / self.total
            text = (f"gfbopt: {self.desc} {self.n}/{self.total} {self.unit} "
                    f"({100.0 * fraction:.0f} %), {_format_seconds(elapsed)}")
            if 0 < self.n < self.total:
                eta = elapsed * (self.total - self.n) / self.n
                text += f", ETA {_format_seconds(eta)}"
        else:
            text = f"gfbopt: {self.desc} {self.n} {self.unit}, {_format_seconds(elapsed)}"
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
