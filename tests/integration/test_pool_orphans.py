"""A forkserver pool's workers end when the driver is killed (kill -9): their parent is the
forkserver, which outlived the driver, so each worker also watches the driver's pid
(gfbopt.parallel._exit_with_parent).  Before, a killed driver left the forkserver and both
workers running a never-ending task (found after tests/integration/test_store_durability's
timer test)."""
import os
import signal
import subprocess
import sys
import time

DRIVER = r"""
import sys, time
from gfbopt.parallel import WorkerPool

def forever(_):
    import os
    print(os.getpid(), flush=True)
    while True:
        time.sleep(0.1)

if __name__ == "__main__":
    with WorkerPool(2, start_method="forkserver") as pool:
        executor = pool.executor(2)
        futures = [executor.submit(forever, k) for k in range(2)]
        time.sleep(60)
"""


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    try:                                   # a zombie is dead too
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().split()[2] != "Z"
    except OSError:
        return False


def test_forkserver_workers_end_when_the_driver_is_killed(tmp_path):
    script = tmp_path / "driver.py"
    script.write_text(DRIVER)
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True,
                            env={**os.environ, "OMP_NUM_THREADS": "1"})
    try:
        workers = [int(proc.stdout.readline()) for _ in range(2)]
        assert all(_alive(p) for p in workers)
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        proc.stdout.close()
    deadline = time.monotonic() + 10.0
    while any(_alive(p) for p in workers) and time.monotonic() < deadline:
        time.sleep(0.2)
    left = [p for p in workers if _alive(p)]
    for p in left:                          # do not leave them behind when the test fails
        os.kill(p, signal.SIGKILL)
    assert left == []
