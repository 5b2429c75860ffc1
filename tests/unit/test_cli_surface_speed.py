"""One speed rule at every one-bearing command: a speed that moves the journal surface above
1000 m/s is refused in one line naming the option, as `gfbopt rotor --speed-range` refuses it
(the reviewer found `gfbopt stability --speed-rpm 3e6` answered with a verdict)."""
import pytest

from cli_inprocess import run_cli

B = "problems/bearings/ruscitto.toml"
COMMANDS = [
    ["stability", "--bearing", B, "--rotor-mass-kg", "2", "--load-newton", "20", "--speed-rpm"],
    ["capacity", "--bearing", B, "--min-film-um", "5", "--speed-rpm"],
    ["static", "--bearing", B, "--load-newton", "20", "--speed-rpm"],
    ["linear", "--bearing", B, "--load-newton", "20", "--speed-rpm"],
]


@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: c[0])
def test_a_speed_above_the_surface_limit_is_refused(command):
    r = run_cli(*command, "3e6")
    err = r.stderr.strip()
    assert r.returncode == 2 and len(err.splitlines()) == 1, err
    # R = 19.05 mm: 1000 m/s is 501,275 rpm, the number gfbopt rotor gives for the blower
    assert "--speed-rpm = 3000000.0" in err and "at most 501275 rpm" in err


def test_max_speed_without_lift_off_has_its_own_reason():
    r = run_cli("capacity", "--bearing", B, "--min-film-um", "5", "--speed-rpm", "30000",
                "--max-speed-rpm", "40000")
    assert r.returncode == 2 and "bounds the lift-off speed" in r.stderr
