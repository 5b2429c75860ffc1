"""Progress reporting: a status line when stderr is not a terminal, a tqdm bar when it is."""
import io

from gfbopt.progress import StatusLine, progress


class _Clock:
    def __init__(self):
        self.t = 0.0

    def __call__(self):
        return self.t


def test_status_line_is_periodic_with_eta():
    clock, out = _Clock(), io.StringIO()
    line = StatusLine(10, "onset scan", "speed", out, interval_s=10.0, clock=clock)
    clock.t = 5.0
    line.update(2)                     # 5 s < interval: nothing written yet
    assert out.getvalue() == ""
    clock.t = 12.0
    line.update(2)                     # 4 of 10 done in 12 s: ETA 18 s
    assert out.getvalue().strip() == "gfbopt: onset scan 4/10 speed (40 %), 12.0 s, ETA 18.0 s"
    line.close()                       # a final line at the end
    assert len(out.getvalue().splitlines()) == 2


def test_non_terminal_stream_gets_status_line_and_terminal_gets_tqdm(monkeypatch):
    monkeypatch.delenv("GFBOPT_PROGRESS", raising=False)
    assert isinstance(progress(3, stream=io.StringIO()), StatusLine)

    class Tty(io.StringIO):
        def isatty(self):
            return True

    bar = progress(3, desc="x", stream=Tty())
    assert type(bar).__module__.startswith("tqdm")
    bar.close()


def test_disabled_by_environment(monkeypatch):
    monkeypatch.setenv("GFBOPT_PROGRESS", "0")
    out = io.StringIO()
    with progress(3, stream=out) as bar:
        bar.update(3)
    assert out.getvalue() == ""
