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


def test_request_constructors_build_schema_valid_requests(proto_schemas):
    from contact_client import request as rq
    from support import validator_for

    check = validator_for(proto_schemas["request"]).validate
    block = rq.body("block", rq.material(200.0, 0.3),
                    rq.rectangle([-1.0, -1.0], 2.0, 1.0, 0.1, grading=rq.grading(0.01, extent=0.2, focus=[0.0, 0.0])),
                    supports=[rq.support("bottom", ux=0.0, uy=0.0)], tractions=[rq.pressure("left", 1.0)])
    roller = rq.body("roller", rq.material(100.0, 0.25), rq.half_disk([3.0, 1.0], 1.0, "down", 0.1))
    req = rq.request(
        bodies=[block, roller],
        obstacles=[rq.obstacle("punch", rq.profile({"flat": {"half_width": 0.5}}),
                               rq.punch(vertical=rq.load(-1.0), horizontal=rq.displacement(0.0),
                                        rotation=rq.displacement(0.0)))],
        foundations=[rq.foundation("soil", rq.winkler(10.0), -5.0, 5.0)],
        contacts=[rq.contact("block", "top", obstacle="punch"),
                  rq.contact("roller", "arc", against=("block", "top"), discretization="mortar"),
                  rq.contact("block", "bottom", foundation="soil")],
        method="active_set", outputs=["displacement"], time_limit=10.0,
    )
    check(req)
    for model in (rq.pasternak(1.0, 0.1), rq.half_plane(1.0, 0.3, 10.0)):
        check(rq.request([block], foundations=[rq.foundation("f", model, -1.0, 1.0)],
                         contacts=[rq.contact("block", "bottom", foundation="f")]))


def test_a_pair_names_exactly_one_target():
    from contact_client import request as rq

    with pytest.raises(ValueError):
        rq.contact("a", "top")
    with pytest.raises(ValueError):
        rq.contact("a", "top", obstacle="o", foundation="f")
