"""The service's operator cache, seen from a client: a repeated scene is a
cache hit with the identical answer; a new prescribed displacement on the same
mesh (the obstacle moved) is a hit too, and the answer follows linear elasticity
exactly."""

from __future__ import annotations

import copy

from scenes_small import square_block


def _pressures(reply):
    return [p["pressure"] for p in reply["pairs"][0]["points"]]


def test_repeat_hits_and_answers_identically(client):
    req = square_block()
    req["description"] = "cache test: " + req["description"]  # a scene no other test sends first
    req["bodies"][0]["material"]["poisson_ratio"] = 0.21
    first = client.solve(req)
    second = client.solve(req)
    assert first["cache"] in ("miss", "hit")
    assert second["cache"] == "hit"
    assert second["timings"]["factorization"] == 0.0
    assert _pressures(first) == _pressures(second)


def test_moved_obstacle_reuses_the_factorization(client):
    req = square_block()
    req["bodies"][0]["material"]["poisson_ratio"] = 0.22
    base = _pressures(client.solve(req))
    deeper = copy.deepcopy(req)
    line = deeper["obstacles"][0]["shape"]["line"]
    line["point"] = [line["point"][0], 2.0 * line["point"][1]]  # push twice as deep
    reply = client.solve(deeper)
    assert reply["cache"] == "hit"  # same mesh, material, supports and contact rows
    ps = _pressures(reply)
    # Uniform uniaxial compression, linear in the push: twice the pressure, still uniform.
    assert max(ps) - min(ps) <= 1e-9 * max(ps)
    assert abs(ps[0] / base[0] - 2.0) < 1e-10
