"""Every scene builder gives a request the service solves, with one physical truth each."""

from __future__ import annotations

import pytest

from contact_client import scenes


def test_roller_on_floor_obeys_hertz(client):
    # Hertz to the 2 % of the Hertz tests (tests/test_hertz.py says where the budget goes).
    r = client.solve(scenes.roller_on_floor())
    assert r["status"] == "solved" and r["resultant"]["fy"] > 0, "the floor pushes the roller up"
    m = scenes.hertz_measure(r)
    a, p0 = scenes.hertz_reference(m["P"], 8.0, 200.0, 0.3)
    assert m["a"] == pytest.approx(a, rel=0.02) and m["p0"] == pytest.approx(p0, rel=0.02)


def test_block_on_polyline_is_pushed_up_by_the_floor(client):
    r = client.solve(scenes.block_on_polyline())
    assert r["status"] == "solved"
    assert r["resultant"]["fy"] > 0, "the floor pushes the block up"
    assert r["pairs"][0]["zones"], "something touches"


def test_block_held_by_contact_carries_its_load_as_a_uniform_pressure(client):
    q = 1.0
    r = client.solve(scenes.block_held_by_contact(pressure=q))
    assert r["status"] == "solved"
    assert r["notes"], "the free sliding is reported"
    # Equilibrium: the floor carries q * width; a uniformly loaded free block on a
    # frictionless rigid floor is in uniform compression, so every candidate carries q.
    assert r["resultant"]["fy"] == pytest.approx(q * 2.0, rel=1e-9)
    for p in r["pairs"][0]["points"]:
        assert p["pressure"] == pytest.approx(q, rel=1e-6)
