"""The design verdict's words for the top-speed orbit read the orbit's statuses: a bearing
without subsynchronous whirl (status 'none', its amplitude null in the orbit's JSON) is said
to have none — before, the text formatted the null amplitude and raised a TypeError."""
import math

from gfbopt.studies.rotor_report import whirl_text

BASE = {"contact": False, "success": True, "revolutions": 40, "grid": "36x10"}


def _bearing(name, status, amplitude, film, settled=False):
    return {"bearing": name, "limit_cycle_status": status,
            "limit_cycle_amplitude_um": amplitude, "min_film_um": film,
            "limit_cycle_settled": settled, "limit_cycle_frequency_hz": math.nan}


def test_no_subsynchronous_whirl_at_either_bearing():
    text = whirl_text({**BASE, "bearings": [_bearing("A", "none", math.nan, 3.1),
                                            _bearing("B", "none", math.nan, 2.9)]}, 45000)
    assert text == ("at 45,000 rpm no subsynchronous whirl (minimum film 2.90 µm; 40 "
                    "revolutions on the 36x10 grid)")


def test_a_limit_cycle_at_one_bearing_and_none_at_the_other():
    text = whirl_text({**BASE, "bearings": [_bearing("A", "limit cycle", 6.5, 3.1, True),
                                            _bearing("B", "none", math.nan, 2.9)]}, 45000)
    assert "6.50 µm at bearing A, none at bearing B" in text and "settled" in text
    assert "nan" not in text
