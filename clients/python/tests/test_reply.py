"""Replies as Reply objects: the CLI's summary as repr, a table of points, raise_for_status."""

from __future__ import annotations

import json
import pickle
import subprocess
import sys

import pytest

from contact_client import NotSolved, Reply, scenes, solve_local
from contact_client.reply import POINT_COLUMNS


def _without_times(text: str) -> list[str]:
    # The one line that differs between two runs of the same solve: its timings.
    return [line for line in text.splitlines() if not line.startswith("time ")]


def test_repr_is_the_cli_summary_of_the_same_solve(contact_bin, hertz_example_path, hertz_example):
    cli = subprocess.run([str(contact_bin), "solve", str(hertz_example_path), "--summary"],
                         capture_output=True, text=True, check=True).stdout
    reply = solve_local(hertz_example)
    assert isinstance(reply, Reply) and isinstance(reply, dict)
    assert _without_times(repr(reply)) == _without_times(cli.strip())
    assert len(repr(reply)) < 2000, "a summary, not the 100k-character dict"


def test_a_service_reply_is_a_reply_with_the_same_summary(hertz_reply, hertz_example):
    assert isinstance(hertz_reply, Reply)
    assert _without_times(repr(hertz_reply)) == _without_times(repr(solve_local(hertz_example)))


def test_a_reply_stays_the_reply_dict():
    reply = solve_local(scenes.hertz_cylinder(h_min=0.04))
    plain = json.loads(json.dumps(reply))
    assert plain == dict(reply) and reply["status"] == "solved"
    again = pickle.loads(pickle.dumps(reply))
    assert type(again) is Reply and again == reply


def test_a_summary_of_a_reply_from_another_version_still_names_status_and_zones():
    reply = solve_local(scenes.hertz_cylinder(h_min=0.04))
    newer = Reply({**reply, "field_of_a_newer_service": 1})
    text = repr(newer)
    assert text.splitlines()[0] == "status       solved"
    (zone,) = reply["pairs"][0]["zones"]
    assert "pair 0       body 'block' against obstacle 'cylinder'" in text
    # Six significant digits as the CLI prints them.
    assert f"zones [{zone[0]:.6f}".rstrip("0") in text


def test_raise_for_status_raises_for_an_uncertified_answer():
    req = scenes.hertz_cylinder(h_min=0.04)
    req["method"], req["settings"] = "interior_point", {"max_iterations": 1}
    reply = solve_local(req, check=False)
    assert reply["status"] == "max_iterations" and not reply.ok
    assert repr(reply).startswith("status       NOT SOLVED")
    with pytest.raises(NotSolved) as err:
        reply.raise_for_status()
    assert err.value.code == "max_iterations" and err.value.reply is reply
    solved = solve_local(scenes.hertz_cylinder(h_min=0.04))
    assert solved.raise_for_status() is solved


def test_points_table_holds_every_candidate_of_every_pair():
    reply = solve_local(scenes.roller_on_plate(load=1.0, h_min=0.04))
    t = reply.points()
    assert tuple(t) == POINT_COLUMNS
    n = sum(len(p["points"]) for p in reply["pairs"])
    assert all(len(col) == n for col in t.values())
    # The table is the reply's points, row for row.
    pts = [q for p in reply["pairs"] for q in p["points"]]
    assert t["pressure"] == [q["pressure"] for q in pts] and t["node"] == [q["node"] for q in pts]
    assert [[a, b] for a, b in zip(t["nx"], t["ny"])] == [q["normal"] for q in pts]
    # Equilibrium read off the table: the normal forces add up to the pair's resultant.
    fy = sum(f * ny for f, ny in zip(t["force"], t["ny"]))
    assert abs(fy) == pytest.approx(abs(reply["pairs"][0]["resultant"]["fy"]), rel=1e-9)


def test_to_dataframe_or_a_clear_import_error(monkeypatch):
    reply = solve_local(scenes.hertz_cylinder(h_min=0.04))
    try:
        import pandas  # noqa: F401
    except ImportError:
        pass
    else:
        df = reply.to_dataframe()
        assert list(df.columns) == list(POINT_COLUMNS) and len(df) == len(reply["pairs"][0]["points"])
        assert df["pressure"].max() == max(q["pressure"] for q in reply["pairs"][0]["points"])
    monkeypatch.setitem(sys.modules, "pandas", None)  # as if pandas were not installed
    with pytest.raises(ImportError, match=r"pip install pandas.*points\(\)"):
        reply.to_dataframe()


def test_notes_carry_their_kinds():
    """Each note has its kind at the same index of ``note_kinds`` (issue 38.2): the
    Winkler footing example's one note is its undetermined horizontal translation,
    and ``notes_of`` picks it by kind; a kind it does not hold gives none."""
    from contact_client import NoteKind
    from support import EXAMPLES

    reply = solve_local(json.loads((EXAMPLES / "foundation_winkler_footing.json").read_text()))
    assert len(reply["note_kinds"]) == len(reply["notes"]) == 1
    assert NoteKind(reply["note_kinds"][0]) is NoteKind.UNDETERMINED_MOTION
    assert reply.notes_of(NoteKind.UNDETERMINED_MOTION) == reply["notes"]
    assert "not determined" in reply["notes"][0]
    assert reply.notes_of(NoteKind.METHOD_FALLBACK) == []
