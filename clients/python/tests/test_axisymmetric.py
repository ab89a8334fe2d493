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
    lame_press_fit_pressure,
    press_fit,
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


def test_press_fit_matches_lame():
    """Frictionless, free ends: plane stress, Lame's pressure over the whole bore; the
    area-weighted mean within 0.5 % (the interference, 0.1 % of the radius, is the
    ambiguity of b), as the Rust test holds it."""
    reply = solve_local(press_fit())
    assert reply["status"] == "solved"
    points = reply["pairs"][0]["points"]
    area = sum(q["weight"] for q in points)
    mean = sum(q["pressure"] * q["weight"] for q in points) / area
    assert abs(mean / lame_press_fit_pressure(1.0, 2.0, 0.001, 200.0) - 1) < 0.005


def test_press_fit_pushed_out_slides_at_mu_times_the_fit_force():
    """Closed with friction mu = 0.05, then pushed 0.01 along the axis (ten times the
    elastic slip): every point of the bore slides at |t| = mu p (1e-9), the push-out
    force (the friction resultant along the axis) is mu times the normal ring force
    (1e-12), and within 1.5 % of mu p 2 pi b L with Lame's p (measured -0.20 % moved by
    the shaft's top, the default, and +0.93 % by its bottom: the friction's axial
    traction changes the fit through nu, by about 0.16 mu)."""
    mu = 0.05
    reply = solve_local(press_fit(friction=mu, push=0.01))
    assert reply["status"] == "solved"
    pushed = reply["steps"][1]["pairs"][0]
    normal = sum(q["force"] for q in pushed["points"])
    for q in pushed["points"]:
        assert q["state"] == "slip"
        assert abs(abs(q["tangential_traction"]) - mu * q["pressure"]) <= 1e-9 * mu * q["pressure"]
    force = abs(pushed["friction"]["tangential_resultant"]["fy"])
    assert abs(force - mu * normal) <= 1e-12 * mu * normal
    lame = lame_press_fit_pressure(1.0, 2.0, 0.001, 200.0) * 2 * math.pi * 0.999 * 1.0
    assert abs(force / (mu * lame) - 1) < 0.015


def test_press_fit_by_default_sticks_as_mu_grows():
    """The issue's ask, "pushing the shaft by its top in scenes.press_fit": by default
    the shaft is held and moved by its top, the far end from the ring's held bottom,
    and the push-out at mu = 100 solves in both steps with no prescribed_slip warning,
    its push-out force that of the Rust test a_press_fit_pulled_by_its_far_end_sticks_as_mu_grows
    (3.2774): the builder makes the same scene for the same core, so 1e-3 pins the builder
    to that scene (a different support or load would move the force by far more).
    Moved by its bottom (both bottoms held), the bore's bottom node at (0.999, 0) has
    its slip prescribed: the reply warns so, naming it, and the step ends at
    max_iterations (push-out force 40.9, growing with mu)."""
    from contact_client import Status, WarningCode

    reply = solve_local(press_fit(friction=100.0, push=0.01))
    assert reply["status"] == Status.SOLVED
    assert [s["status"] for s in reply["steps"]] == ["solved", "solved"]
    assert all(w["code"] != WarningCode.PRESCRIBED_SLIP for w in reply.get("warnings", []))
    force = reply["steps"][1]["pairs"][0]["friction"]["tangential_resultant"]["fy"]
    assert abs(force / 3.2774 - 1) < 1e-3

    bottom = solve_local(press_fit(friction=100.0, push=0.01, shaft_end="bottom"), check=False)
    assert bottom["status"] == Status.MAX_ITERATIONS
    held = [w for w in bottom["warnings"] if w["code"] == WarningCode.PRESCRIBED_SLIP]
    assert len(held) == 1 and held[0]["location"] == "/contacts/0"
    assert "at (0.999, 0)" in held[0]["message"]


def _hertz_l2(reply: dict, a: float, p0: float) -> float:
    """Relative L2 error of the nodal pressure over [0, a] against Hertz, weighted by
    the ring's tributary area (weight times r)."""
    pts = [q for q in reply["pairs"][0]["points"] if q["x"] < a]
    err = sum(q["weight"] * q["x"] * (q["pressure"] - hertz_pressure(q["x"], a, p0)) ** 2 for q in pts)
    ref = sum(q["weight"] * q["x"] * hertz_pressure(q["x"], a, p0) ** 2 for q in pts)
    return math.sqrt(err / ref)


def test_ball_on_flat_takes_an_accuracy_and_meets_it():
    # ball_on_flat(accuracy=) raised TypeError though request.accuracy's docstring
    # sends users to the builders' accuracy=. Under load control P = 2 exactly, so
    # Hertz's a and p0 are known before the solve: the default mesh is 1.3 % off in
    # L2 (above a 1 % target), the refined answer 0.4 % (measured).
    from contact_client import request as rq

    a, p0 = hertz_sphere_reference(2.0, 10.0, 200.0, 0.3)
    plain = solve_local(ball_on_flat(load=2.0))
    assert _hertz_l2(plain, a, p0) > 0.01
    req = ball_on_flat(load=2.0, accuracy=rq.accuracy(pressure_l2=0.01))
    assert req["settings"] == {"accuracy": {"pressure_l2": 0.01}}
    reply = solve_local(req)
    assert reply["refinement"]["reached"] and len(reply["refinement"]["rounds"]) >= 2
    assert _hertz_l2(reply, a, p0) < 0.01


def _contact_radius(solid: dict) -> float:
    """a from a least-squares line of p^2 against r^2 over the points in contact
    (Hertz's p^2 = p0^2 (1 - r^2/a^2) is one): a^2 = -intercept / slope."""
    pts = [(q["at"][0] ** 2 + q["at"][1] ** 2, q["pressure"] ** 2) for q in solid["points"] if q["in_contact"]]
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    slope = sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)
    return math.sqrt((slope * mx - my) / slope)


def test_ball_on_flat_3d_matches_hertz():
    """The 3D quarter model (T10, cells a/5 at the apex): the apex pressure within
    3 % of p0 (0.984 measured: a corner row's pressure is a weighted mean over its
    faces, below a concave peak), the quarter's force the load / 4 to round-off, and
    a from a least-squares line of p^2 against r^2 (Hertz's p makes it one) within
    2 % (1.006 measured)."""
    from contact_client.scenes import ball_on_flat_3d

    load, radius = 6153.846153846154, 50.0
    reply = solve_local(ball_on_flat_3d(load=load, radius=radius))
    assert reply["status"] == "solved"
    solid = reply["solid"]
    assert abs(solid["resultant"]["force"][2] - load / 4) < 1e-9 * load
    a, p0 = hertz_sphere_reference(load, radius, 210000.0, 0.3)
    (patch,) = solid["patches"]
    assert abs(patch["peak_pressure"] / p0 - 1) < 0.03
    a_h = _contact_radius(solid)
    assert abs(a_h / a - 1) < 0.02


def test_sphere_into_block_3d_matches_hertz(client):
    """A rigid sphere pressed into a block (3D quarter, T10, cells a/5 at the apex),
    solved by the service: the quarter's force -load / 4 to round-off, the apex
    pressure within 5 % of p0 (0.987 measured) and a from the line of p^2 against
    r^2 within 3 % (1.006 measured), the bounds of crates/contact/tests/solid_obstacles.rs."""
    from contact_client.scenes import sphere_into_block_3d

    load, radius = 6153.846153846154, 50.0
    reply = client.solve(sphere_into_block_3d(load=load, radius=radius))
    assert reply["status"] == "solved"
    solid = reply["solid"]
    assert abs(solid["resultant"]["force"][2] + load / 4) < 1e-9 * load
    a, p0 = hertz_sphere_reference(load, radius, 210000.0, 0.3)
    (patch,) = solid["patches"]
    assert abs(patch["peak_pressure"] / p0 - 1) < 0.05
    a_h = _contact_radius(solid)
    assert abs(a_h / a - 1) < 0.03
