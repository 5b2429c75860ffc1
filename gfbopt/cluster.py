"""Running tasks on a Dask distributed cluster (``gfbopt run --scheduler ADDRESS``).

**A scheduler is trusted code.**  ``distributed`` unpickles what the scheduler and workers
send: connecting to a scheduler runs whatever it chooses on your machine, and the workers run
gfbopt's tasks with your data.  Connect only to a cluster you (or your site) run, on the
loopback address or a private network; across networks you do not control use ``tls://``
with certificates (docs/doe.md, "Dask").

* :func:`connect_scheduler` checks the address before connecting — ``tcp://`` or ``tls://``
  (``tls://`` needs the Dask TLS configuration: ``distributed.comm.tls.ca-file``,
  ``...client.cert`` and ``...client.key``), other schemes refused — then asks the
  scheduler who it is with a wall-clock time-out, so a port that is not a scheduler is one
  line after ``timeout`` seconds, never a hang.
* :func:`stream_dask` runs the tasks and yields each result as it finishes.  While no
  worker is connected it reports a status line (every ``status_every`` seconds) and gives
  up after ``worker_timeout`` seconds; a worker killed under a task (``KilledWorker``) is
  retried a bounded number of times, then reported as an infrastructure failure (not a
  result of the points); a lost scheduler raises :class:`gfbopt.parallel.InfrastructureError`
  at once.

**A million points.**  Each argument of :func:`stream_dask` is a *chunk* (a study's
``chunk_size`` neighbouring points, whose rows depend on nothing else), and one Dask task
carries several whole chunks (:func:`call_batch`), so the rows are those of the process
pool whatever the grouping.  Dask costs milliseconds per task, so tasks are sized from
measured work (:func:`task_size`):

* the first tasks are one chunk each; every finished task adds its in-worker seconds and
  its chunks to the measurement (seconds per chunk = their ratio, over the whole run);
* then a task is ``task_seconds / seconds_per_chunk`` chunks — ``task_seconds`` of work
  (default :data:`TASK_SECONDS` = 20 s, chosen in [10, 60] s) — but at most
  :data:`GROWTH` (4) times the largest finished task (a ramp: a few fast chunks never
  make one huge task), at most :data:`MAX_TASK_CHUNKS`, and at most
  ``ceil(remaining / (2 × workers))`` chunks, so every worker has work to the end (the
  last tasks are shorter);
* :func:`in_flight` tasks (two per connected worker) are on the cluster at once; finished
  ones are replaced in one ``client.map`` call, and ``distributed.as_completed`` wakes the
  driver when one finishes: the driver never holds more than a few futures, nor scans them.

A task's rows arrive when the whole task finishes: a ``kill -9`` of the driver loses the
tasks being computed (at most ``task_seconds`` of work per worker) and the rows not yet
written (``flush_s``, :mod:`gfbopt.doe.engine`); a resume computes them.  A killed task's
chunks are sent again in two halves (so a chunk that kills its worker takes fewer others
with it).
"""
from __future__ import annotations

import math
import time
import uuid
from collections.abc import Callable
from typing import Optional

from .errors import ParameterError
from .runtime import InfrastructureError, InfrastructureFailure
from .runtime import call_task as _call_task

#: schemes gfbopt connects to
SCHEMES = ("tcp", "tls")
#: seconds without any connected worker before a run gives up
WORKER_TIMEOUT_S = 120.0
#: seconds between two status lines while no worker is connected
STATUS_EVERY_S = 10.0
#: seconds of work a Dask task is sized to once the first chunks are measured, and the
#: range a caller may choose it in
TASK_SECONDS = 20.0
TASK_SECONDS_RANGE = (10.0, 60.0)
#: most chunks in one task (bounds one task's message: its points and its rows)
MAX_TASK_CHUNKS = 10_000
#: a task holds at most this many times the chunks of the largest finished one (a ramp)
GROWTH = 4


def _security(address: str):
    """The Dask TLS configuration for a ``tls://`` address (ParameterError when absent)."""
    from distributed.security import Security

    security = Security()
    if address.startswith("tls://"):
        args = security.get_connection_args("client")
        if args.get("ssl_context") is None:
            raise ParameterError("--scheduler", address, "tls:// needs a TLS configuration: "
                                 "set distributed.comm.tls.ca-file, .client.cert and "
                                 ".client.key in the Dask config (docs/doe.md, Dask)")
    return security


def check_address(address) -> str:
    """``address`` as a scheduler address (``host:port`` means ``tcp://host:port``), or a
    ParameterError naming the rule."""
    if not isinstance(address, str) or not address.strip():
        raise ParameterError("--scheduler", address, "must be a scheduler address such as "
                             "tcp://127.0.0.1:8786")
    address = address.strip()
    scheme, sep, rest = address.partition("://")
    if not sep:
        scheme, rest, address = "tcp", address, f"tcp://{address}"
    if scheme == "ucx":
        raise ParameterError("--scheduler", address, "ucx:// is not supported by gfbopt "
                             "(it needs ucx-py and a UCX network); use tcp:// or tls://")
    if scheme not in SCHEMES:
        raise ParameterError("--scheduler", address, f"scheme {scheme}:// is not supported "
                             "(use tcp:// or tls://)")
    host, colon, port = rest.rpartition(":")
    if not colon or not host or not port.isdigit() or not 0 < int(port) < 65536:
        raise ParameterError("--scheduler", address, "must be SCHEME://HOST:PORT, e.g. "
                             "tcp://127.0.0.1:8786")
    return address


def _identify(address: str, security, timeout: float) -> dict:
    """The scheduler's identity, or an error, within ``timeout`` seconds of wall clock."""
    import asyncio

    from distributed.comm import connect

    async def ask() -> dict:
        comm = await connect(address, timeout=timeout,
                             **security.get_connection_args("client"))
        try:
            await comm.write({"op": "identity"})
            return await comm.read()
        finally:
            await comm.close()

    async def bounded() -> dict:
        return await asyncio.wait_for(ask(), timeout)

    return asyncio.run(bounded())


def connect_scheduler(address: str, timeout: float = 10.0):
    """A ``distributed.Client`` on the Dask scheduler at ``address``; one ParameterError
    naming the address when it is malformed, unsupported or cannot be reached within
    ``timeout`` seconds (or dask.distributed is not installed)."""
    address = check_address(address)
    try:
        from distributed import Client
    except ImportError:  # pragma: no cover - optional extra
        raise ParameterError("--scheduler", address, "needs dask[distributed] "
                             "(pip install 'gfbopt[distributed]')") from None
    security = _security(address)
    try:
        identity = _identify(address, security, timeout)
    except Exception as exc:  # noqa: BLE001 - every failure to reach it is one line
        text = (str(exc).splitlines() or [""])[0][:120]
        raise ParameterError("--scheduler", address, f"cannot be reached within {timeout:g} s "
                             f"({type(exc).__name__}{': ' + text if text else ''})") from None
    if not isinstance(identity, dict) or identity.get("type") != "Scheduler":
        raise ParameterError("--scheduler", address, "answered, but is not a Dask scheduler")
    try:
        return Client(address, timeout=timeout, set_as_default=False, security=security)
    except Exception as exc:  # noqa: BLE001
        raise ParameterError("--scheduler", address, f"refused the connection "
                             f"({type(exc).__name__})") from None


def quiet_logs() -> None:
    """Keep distributed's own log records (reconnection attempts, their tracebacks) off the
    terminal: gfbopt reports a lost scheduler or worker in one line of its own."""
    import logging

    import distributed  # noqa: F401 - its import configures its loggers: set them after

    for name in ("distributed", "distributed.client", "distributed.comm",
                 "distributed.core", "distributed.utils", "distributed.worker"):
        logging.getLogger(name).setLevel(logging.CRITICAL)


def worker_count(client) -> int:
    """Workers connected to the client's scheduler (0 when it cannot be asked)."""
    try:
        return len(client.scheduler_info().get("workers", {}))
    except Exception:  # noqa: BLE001 - a lost scheduler has no workers
        return 0


def _lost(client) -> bool:
    return getattr(client, "status", "running") not in ("running", "newly-created")


def task_size(seconds_per_chunk: Optional[float], *, remaining: int, workers: int,
              largest: int, target_s: float = TASK_SECONDS) -> int:
    """Chunks in the next Dask task (the sizing rule of the module docstring).

    ``seconds_per_chunk``: the measured work per chunk (None before any task finished);
    ``remaining``: chunks not yet sent; ``workers``: workers connected; ``largest``: chunks
    in the largest task finished so far.  Before a measurement a task is one chunk; then
    ``target_s / seconds_per_chunk`` chunks (``target_s`` seconds of work), but at most
    :data:`GROWTH` times the largest finished task, at most :data:`MAX_TASK_CHUNKS`, and at
    most ``ceil(remaining / (2 workers))`` so every worker gets a share to the end."""
    if remaining <= 0:
        return 0
    if seconds_per_chunk is None or largest < 1:
        return 1
    size = target_s / max(float(seconds_per_chunk), 1e-9)
    size = min(size, GROWTH * largest, MAX_TASK_CHUNKS,
               math.ceil(remaining / (2 * max(1, workers))))
    return int(max(1, min(size, remaining)))


def check_task_seconds(target_s) -> float:
    """``target_s`` as a number of seconds within :data:`TASK_SECONDS_RANGE`."""
    low, high = TASK_SECONDS_RANGE
    if isinstance(target_s, bool) or not isinstance(target_s, (int, float)) or \
            not low <= target_s <= high:
        raise ParameterError("task_seconds", target_s, f"must be a number of seconds in "
                             f"[{low:g}, {high:g}]")
    return float(target_s)


def in_flight(workers: int) -> int:
    """Tasks kept on the cluster at once: two per connected worker (one running, one
    queued behind it, so no worker waits for the driver), at least two."""
    return 2 * max(1, int(workers))


def call_batch(function: Callable, arguments: list) -> tuple:
    """One Dask task: ``function`` on each argument (a chunk) in turn, in the worker;
    returns (seconds spent, the results; an exception is a result)."""
    t0 = time.perf_counter()
    results = [_call_task(function, argument) for argument in arguments]
    return time.perf_counter() - t0, results


def _wait(ready: Callable[[], bool], condition, seconds: float) -> None:
    """Sleep until ``ready()`` or ``seconds`` passed (woken by the as_completed set)."""
    if condition is None:
        time.sleep(seconds)
        return
    with condition:
        if not ready():
            condition.wait(timeout=seconds)


def stream_dask(function: Callable, arguments: list, client, *, retries: int = 2,
                tick: Optional[float] = None, status: Optional[Callable[[str], None]] = None,
                worker_timeout: float = WORKER_TIMEOUT_S, status_every: float = STATUS_EVERY_S,
                task_seconds: float = TASK_SECONDS):
    """Yield ``(k, function(arguments[k]))`` as the tasks finish on the cluster (see the
    module docstring); ``(None, None)`` every ``tick`` seconds while nothing finishes."""
    from collections import deque
    from functools import partial

    from distributed import as_completed

    task_seconds = check_task_seconds(task_seconds)
    run = uuid.uuid4().hex[:8]
    attempts = [0] * len(arguments)
    fresh = deque(range(len(arguments)))        # chunks never sent
    again: deque = deque()                        # chunk lists to send again (killed)
    running: dict = {}                            # future -> its chunks
    done = as_completed(loop=client.loop)
    measured = {"seconds": 0.0, "chunks": 0, "largest": 0}
    serial = iter(range(1 << 62))
    batch = partial(call_batch, function)
    address = getattr(client, "scheduler", None)
    address = getattr(address, "address", "the scheduler")
    now = time.monotonic()
    last_yield = last_status = now
    workers, last_check = worker_count(client), now
    without_workers_since = None

    def lost() -> InfrastructureError:
        return InfrastructureError(f"the Dask scheduler at {address} was lost")

    def send() -> None:
        groups = []
        while len(running) + len(groups) < in_flight(workers) and (again or fresh):
            if again:
                groups.append(again.popleft())
                continue
            per = (measured["seconds"] / measured["chunks"] if measured["chunks"] else None)
            size = task_size(per, remaining=len(fresh), workers=workers,
                             largest=measured["largest"], target_s=task_seconds)
            groups.append([fresh.popleft() for _ in range(size)])
        if not groups:
            return
        keys = [f"gfbopt-{run}-{next(serial)}" for _ in groups]
        futures = client.map(batch, [[arguments[k] for k in g] for g in groups], key=keys,
                             pure=False)
        running.update(zip(futures, groups))
        done.update(futures)

    try:
        while running or fresh or again:
            send()
            finished = done.next_batch(block=False)
            now = time.monotonic()
            checked = now - last_check >= 2.0
            if checked:                           # one scheduler call every 2 s at most
                last_check, workers = now, worker_count(client)
            if not finished:
                if _lost(client):
                    raise lost()
                if checked and workers == 0:
                    without_workers_since = without_workers_since or now
                    waited = now - without_workers_since
                    if waited >= worker_timeout:
                        raise InfrastructureError(
                            f"no Dask worker connected to {address} for {waited:.0f} s")
                    if status is not None and now - last_status >= status_every:
                        last_status = now
                        status(f"waiting for Dask workers at {address}: 0 connected, "
                               f"{waited:.0f} s (gives up after {worker_timeout:.0f} s)")
                elif checked:
                    without_workers_since = None
                if tick is not None and now - last_yield >= tick:
                    last_yield = now
                    yield None, None
                _wait(done.has_ready, getattr(done, "thread_condition", None), 0.1)
                continue
            for future in finished:
                chunks = running.pop(future)
                if future.status == "finished":
                    try:
                        seconds, results = future.result(timeout=60)
                    except Exception as exc:  # noqa: BLE001 - the result could not travel
                        if _lost(client) or type(exc).__name__ in ("CommClosedError",
                                                                   "TimeoutError"):
                            raise lost() from None
                        seconds, results = None, [exc] * len(chunks)
                    if seconds is not None:
                        measured["seconds"] += seconds
                        measured["chunks"] += len(chunks)
                        measured["largest"] = max(measured["largest"], len(chunks))
                    for k, result in zip(chunks, results):
                        last_yield = time.monotonic()
                        yield k, result
                    continue
                if _lost(client):
                    raise lost()
                error = future.exception() if future.status == "error" else None
                if error is not None and type(error).__name__ != "KilledWorker":
                    for k in chunks:
                        yield k, error
                    continue
                for k in chunks:
                    attempts[k] += 1
                retry = [k for k in chunks if attempts[k] <= retries]
                for k in chunks:
                    if attempts[k] > retries:
                        yield k, InfrastructureFailure(
                            f"the task was lost {attempts[k]} times on the Dask cluster "
                            "(workers killed); not a result of these points")
                half = max(1, math.ceil(len(retry) / 2))   # a chunk that kills its worker
                again.extend(retry[i:i + half] for i in range(0, len(retry), half))
    except BaseException:
        if not _lost(client) and running:
            client.cancel(list(running))
        raise
