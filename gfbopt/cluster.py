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
  worker is connected it reports a status line (every ``tick`` seconds) and gives up after
  ``worker_timeout`` seconds; a worker killed under a task (``KilledWorker``) is retried a
  bounded number of times, then reported as an infrastructure failure (not a result of the
  points); a lost scheduler raises :class:`gfbopt.parallel.InfrastructureError` at once.
"""
from __future__ import annotations

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


def stream_dask(function: Callable, arguments: list, client, *, retries: int = 2,
                tick: Optional[float] = None, status: Optional[Callable[[str], None]] = None,
                worker_timeout: float = WORKER_TIMEOUT_S, status_every: float = STATUS_EVERY_S):
    """Yield ``(k, result)`` as the tasks finish on the cluster (see the module docstring);
    ``(None, None)`` every ``tick`` seconds while nothing finishes."""
    from distributed.client import FutureCancelledError  # noqa: F401 - documents the cause

    run = uuid.uuid4().hex[:8]
    attempts = [0] * len(arguments)

    def submit(k: int):
        return client.submit(_call_task, function, arguments[k], pure=False,
                             key=f"gfbopt-{run}-{k}-{attempts[k]}")

    futures = {submit(k): k for k in range(len(arguments))}
    address = getattr(client, "scheduler", None)
    address = getattr(address, "address", "the scheduler")
    last_yield = last_check = last_status = time.monotonic()
    without_workers_since = None
    try:
        while futures:
            finished = [f for f in futures if f.status != "pending"]
            now = time.monotonic()
            if not finished:
                if _lost(client):
                    raise InfrastructureError(f"the Dask scheduler at {address} was lost")
                if now - last_check >= 2.0:
                    last_check = now
                    if worker_count(client) == 0:
                        without_workers_since = without_workers_since or now
                        waited = now - without_workers_since
                        if waited >= worker_timeout:
                            raise InfrastructureError(
                                f"no Dask worker connected to {address} for {waited:.0f} s")
                        if status is not None and now - last_status >= status_every:
                            last_status = now
                            status(f"waiting for Dask workers at {address}: 0 connected, "
                                   f"{waited:.0f} s (gives up after {worker_timeout:.0f} s)")
                    else:
                        without_workers_since = None
                if tick is not None and now - last_yield >= tick:
                    last_yield = now
                    yield None, None
                time.sleep(0.05)
                continue
            for future in finished:
                k = futures.pop(future)
                if future.status == "finished":
                    try:
                        result = future.result(timeout=60)
                    except Exception as exc:  # noqa: BLE001 - the result could not travel
                        if _lost(client) or type(exc).__name__ in ("CommClosedError",
                                                                   "TimeoutError"):
                            raise InfrastructureError(f"the Dask scheduler at {address} was "
                                                      "lost") from None
                        result = exc
                    last_yield = time.monotonic()
                    yield k, result
                    continue
                if _lost(client):
                    raise InfrastructureError(f"the Dask scheduler at {address} was lost")
                error = future.exception() if future.status == "error" else None
                if error is not None and type(error).__name__ != "KilledWorker":
                    yield k, error
                    continue
                attempts[k] += 1
                if attempts[k] > retries:
                    yield k, InfrastructureFailure(f"the task was lost {attempts[k]} times on "
                                                   "the Dask cluster (workers killed); not a "
                                                   "result of these points")
                else:
                    futures[submit(k)] = k
    except BaseException:
        if not _lost(client):
            client.cancel(list(futures))
        raise
