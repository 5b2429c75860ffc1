"""``--rotor``/``--top-speed`` leave none of the shipped rotor's text in the answer: the title
and notes of problems/rotor_bearing_design.toml describe its 3.2 kg blower and 45,000 rpm, so
on the user's rotor they are rewritten / replaced, and one note says so."""
from __future__ import annotations

from pathlib import Path

from gfbopt.inputs import read_toml
from gfbopt.studies import SCHEMAS
from gfbopt.studies.user_rotor import on_user_rotor

ROOT = Path(__file__).resolve().parents[2]
STUDY = ROOT / "problems" / "rotor_bearing_design.toml"
FLEX = ROOT / "problems" / "rotors" / "flexible_rotor.toml"


def _run(rotor, top):
    data = read_toml(STUDY)
    assert "3.2 kg" in data["title"] and "45,000 rpm" in data["title"]   # the shipped text
    return on_user_rotor(data, str(STUDY), SCHEMAS[data["kind"]], rotor, top,
                         data["name"])


def test_the_users_rotor_and_top_speed_replace_the_shipped_text():
    out = _run(str(FLEX), 30000)
    text = " ".join([out["title"], *out["notes"]])
    assert "flexible_rotor.toml to 30,000 rpm" in out["title"] and "5.08 kg" in out["title"]
    assert "3.2 kg" not in text and "45,000 rpm" not in out["title"]
    assert "blower.toml (3.2" not in text and "top speed 45,000 rpm;" not in text
    assert len(out["notes"]) == 1
    assert "from 4,000 to 30,000 rpm" in out["notes"][0]
    assert "were replaced" in out["notes"][0]


def test_the_top_speed_alone_drops_only_the_notes_naming_the_old_one():
    data = read_toml(STUDY)
    out = _run(None, 30000)
    assert "45,000" not in " ".join([out["title"], *out["notes"][1:]])
    assert "which described the top speed 45,000 rpm, were replaced" in out["notes"][0]
    kept = [n for n in data["notes"] if "45,000" not in n]
    assert out["notes"][1:] == kept and len(kept) == len(data["notes"]) - 1
    assert "1 of its notes" in out["notes"][0]
