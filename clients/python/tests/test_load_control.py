"""The builders' ``load=`` scenes: a body held only by contact and its load, solved
in process, against equilibrium and the closed forms."""

from __future__ import annotations

import math

import pytest

from contact_client import ContactError, closed_forms, scenes, solve_local

# Equilibrium of a body held only by contact: the contact resultant is the load. The
# certificate holds the normwise backward error of equilibrium under the tolerance
# 1e-8, so the resultant may differ from the load by that relative amount.
EQUILIBRIUM = 1e-8


def _hertz_check(reply, P, ref, a_tol, p0_tol):
    pair = reply["pairs"][0]
    assert abs(pair["resultant"]["fy"]) == pytest.approx(P, rel=EQUILIBRIUM)
    assert abs(reply["resultant"]["fy"]) == pytest.approx(P, rel=EQUILIBRIUM)
    a, p0 = ref(P)
    (zone,) = pair["zones"]
    half = 0.5 * (zone[1] - zone[0]) if zone[0] < -1e-12 else zone[1]
    assert half == pytest.approx(a, rel=a_tol)
    assert max(p["pressure"] for p in pair["points"]) == pytest.approx(p0, rel=p0_tol)


def test_hertz_cylinder_under_a_load_is_hertz_with_that_load():
    # Hertz with P the prescribed load. The zone ends are node positions (h_min/a =
    # 0.01/0.68 = 1.5 %, so a within 3 %); the nodal peak measured -0.7 % (2 %).
    P = 10.0
    req = scenes.hertz_cylinder(load=P)
    assert req["bodies"][0]["supports"] == [{"edges": "bottom", "ux": 0.0}]
    reply = solve_local(req)
    _hertz_check(reply, P, lambda P: closed_forms.hertz_reference(P, 8.0, 200.0, 0.3), 0.03, 0.02)
    # The circle pushes the block down; the loads have no moment, nor has the contact.
    assert reply["resultant"]["fy"] < 0 and abs(reply["resultant"]["m"]) < EQUILIBRIUM * P * 8.0


def test_roller_on_floor_under_a_load_is_hertz_with_that_load():
    # a/h_min ~ 48: zone within 3 %; peak measured +0.1 % (2 %).
    P = 5.0
    reply = solve_local(scenes.roller_on_floor(load=P))
    _hertz_check(reply, P, lambda P: closed_forms.hertz_reference(P, 8.0, 200.0, 0.3), 0.03, 0.02)
    assert not reply.get("notes"), "ux = 0 on the flat fixes the sideways slide: nothing is undetermined"


def test_roller_on_plate_under_a_load_is_two_body_hertz_with_that_load():
    # a/h_min ~ 42 (the plate's nodes are 1.3 h_min apart): zone within 3 %, peak 2 %.
    P = 1.0
    reply = solve_local(scenes.roller_on_plate(load=P))
    _hertz_check(reply, P, lambda P: closed_forms.hertz_two_cylinders(P, 8.0, math.inf, 200.0, 0.3, 70.0, 0.33),
                 0.03, 0.02)
    pair = reply["pairs"][0]
    assert pair["other_resultant"]["fy"] == pytest.approx(-pair["resultant"]["fy"], rel=1e-12)


def test_ball_on_flat_under_a_load_is_3d_hertz_with_that_load():
    # The load of the displacement-controlled default (about 7.7): a/h_min ~ 43, zone
    # within one node (2.3 %) and peak within 1 %, as the displacement scene's test.
    P = 7.7
    req = scenes.ball_on_flat(load=P)
    assert req["bodies"][0]["supports"] == [], "the axial translation is the ball's only rigid motion"
    reply = solve_local(req)
    _hertz_check(reply, P, lambda P: closed_forms.hertz_sphere_reference(P, 10.0, 200.0, 0.3), 0.023, 0.01)


def test_a_roller_with_no_support_has_its_slide_reported_as_undetermined():
    # The hand-written pattern's other choice: leave the sideways slide to the service.
    P = 5.0
    req = scenes.roller_on_floor(load=P)
    req["bodies"][0]["supports"] = []
    reply = solve_local(req)
    assert reply["pairs"][0]["resultant"]["fy"] == pytest.approx(P, rel=EQUILIBRIUM)
    (note,) = reply["notes"]
    assert "translation in x" in note and "'roller'" in note and "not determined" in note


def test_load_and_displacement_are_one_or_the_other():
    with pytest.raises(ValueError, match="either"):
        scenes.roller_on_floor(approach=0.05, load=5.0)
    with pytest.raises(ValueError, match="positive"):
        scenes.hertz_cylinder(load=-1.0)
    # A load pulling the body off: refused by the service, not built wrongly.
    req = scenes.roller_on_floor(load=5.0)
    req["bodies"][0]["tractions"][0]["pressure"] *= -1.0
    with pytest.raises(ContactError) as err:
        solve_local(req)
    assert err.value.code in ("incompatible_loads", "no_support")
