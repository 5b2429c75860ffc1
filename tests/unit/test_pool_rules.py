"""The worker pool's rules, as pure functions: how many workers ``gfbopt run`` takes when
``--workers`` is not given (the free cores), and how the workers start (fork only where it
is safe)."""
import pytest

from gfbopt.parallel import choose_start_method, default_workers


@pytest.mark.parametrize("cores, load, workers", [
    (2, 0.0, 2), (2, 0.17, 2), (2, 0.5, 2), (2, 0.51, 1), (2, 1.0, 1), (2, 2.0, 1),
    (2, 5.0, 1), (1, 0.0, 1), (8, 2.7, 5), (8, 2.4, 6), (8, 0.0, 8), (8, -1.0, 8),
    (4, float("nan"), 1), (4, float("inf"), 1)])
def test_the_default_worker_count_is_the_free_cores(cores, load, workers):
    """Cores minus the one-minute load, rounded to whole cores, between 1 and the cores (the
    old default was the cores whatever the load: 2 on a 2-core machine at load 5)."""
    assert default_workers(cores, load) == workers


def test_the_default_never_exceeds_the_cores_nor_the_free_cores_by_half_a_core():
    for cores in range(1, 17):
        for tenth in range(0, 200):
            load = tenth / 10
            n = default_workers(cores, load)
            assert 1 <= n <= cores
            assert n == 1 or n <= cores - load + 0.5


@pytest.mark.parametrize("platform, threads, openmp, method", [
    ("linux", 0, False, "fork"),
    ("linux", 1, False, "forkserver"),      # another Python thread may hold a lock
    ("linux", 0, True, "forkserver"),       # libgomp's thread pool does not survive fork
    ("darwin", 0, False, "forkserver"),     # macOS frameworks are not fork-safe
    ("win32", 0, False, "spawn")])
def test_workers_are_forked_only_where_it_is_safe(platform, threads, openmp, method):
    assert choose_start_method(platform, threads, openmp) == method


def test_the_command_lines_progress_bar_leaves_the_driver_forkable(monkeypatch):
    """On a terminal ``gfbopt run`` draws tqdm bars before its pool starts; tqdm's monitor
    thread made the driver multi-threaded, so the pool fell back to the forkserver."""
    import io
    import sys
    import threading

    import tqdm

    from gfbopt.cli.run import _Progress
    class Terminal(io.StringIO):
        def isatty(self):
            return True

    monkeypatch.setattr(sys, "stderr", Terminal())
    monkeypatch.delenv("GFBOPT_PROGRESS", raising=False)
    monkeypatch.setattr(tqdm.tqdm, "monitor_interval", tqdm.tqdm.monitor_interval)
    before = threading.active_count()
    bar = _Progress("study")
    bar(0.25)
    try:
        assert bar.bar is not None and "study" in sys.stderr.getvalue()
        # the bar started no thread (a one-thread driver forks: see the test above)
        assert threading.active_count() == before
    finally:
        bar.close()
