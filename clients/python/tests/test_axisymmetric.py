"""Bodies of revolution, solved in process, against the 3D closed forms."""

from __future__ import annotations

import math

from contact_client import solve_local
from contact_client.scenes import (
    ball_on_flat,
    boussinesq_pressure,
    boussinesq_settlement,
    flat_punch_of_revolution,
    hertz_pressure,
    hertz_sphere_reference,
)


def test_ball_on_flat_matches_3d_hertz():
    """Nodes 0.015 apart (2.3 % of a): the zone [0, a] ends within one node of
    Hertz's a, the peak within 1 %, the area-weighted L2 within 1 %."""
    reply = solve_local(ball_on_flat())
    assert reply["status"] == "solved"
    P = reply["resultant"]["fy"]
    assert P > 0 and reply["resultant"]["fx"] == 0.0
    a, p0 = hertz_sphere_reference(P, 10.0, 200.0, 0.3)
    pair = reply["pairs"][0]
    (zone,) = pair["zones"]
    assert zone[0] == 0.0 or abs(zone[0]) < 1e-12
    assert abs(zone[1] / a - 1) < 0.023
    peak = max(q["pressure"] for q in pair["points"])
    assert abs(peak / p0 - 1) < 0.01
    num = sum(q["weight"] * (q["pressure"] - hertz_pressure(q["x"], a, p0)) ** 2 for q in pair["points"])
    den = sum(q["weight"] * hertz_pressure(q["x"], a, p0) ** 2 for q in pair["points"])
    assert math.sqrt(num / den) < 0.01
    # Weights are ring areas: they add up to the area of the candidates' annuli,
    # of the order of 2 pi r dr, not of lengths.
    assert sum(q["weight"] for q in pair["points"] if q["x"] < a) > math.pi * (0.9 * a) ** 2


def test_flat_punch_of_revolution_matches_boussinesq():
    """Pressure within 1.5 % up to r = 0.75 a; settlement within 2 % of the
    half-space's (the cylinder of 80 a settles 1.7 % less, measured)."""
    reply = solve_local(flat_punch_of_revolution())
    assert reply["status"] == "solved"
    assert abs(reply["resultant"]["fy"] + 100.0) < 1e-9
    for q in reply["pairs"][0]["points"]:
        if q["x"] <= 0.75:
            assert abs(q["pressure"] / boussinesq_pressure(q["x"], 100.0, 1.0) - 1) < 0.015, q
    settlement = -reply["punches"][0]["alpha2"]
    assert abs(settlement / boussinesq_settlement(100.0, 1.0, 200.0, 0.3) - 1) < 0.02
