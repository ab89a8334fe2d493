"""Rigid punches through zenoh: Sadowsky and Hertz references, and the
structured refusal of loads no contact can balance."""

from __future__ import annotations

import pytest

from contact_client import ContactError, closed_forms, scenes


def test_flat_punch_sadowsky(client):
    reply = client.solve(scenes.punch_on_block({"flat": {"half_width": 1.0}}, load=10.0))
    assert reply["status"] == "solved"
    assert abs(reply["resultant"]["fy"] + 10.0) < 1e-9
    punch = reply["punches"][0]
    assert punch["unique"] is False  # a frictionless flat punch may slide
    # Away from the singular corners the nodal pressure follows P/(pi sqrt(b^2-x^2));
    # 2 % covers the mesh (h = b/100) and the block's finite depth (20 b).
    for p in reply["pairs"][0]["points"]:
        if abs(p["x"]) <= 0.8:
            exact = closed_forms.sadowsky_pressure(p["x"], 10.0, 1.0)
            assert abs(p["pressure"] / exact - 1.0) < 0.02


def test_circular_punch_hertz(client):
    reply = client.solve(scenes.punch_on_block({"circle": {"radius": 8.0}}, load=10.0, extent=0.8))
    a, p0 = closed_forms.hertz_reference(10.0, 8.0, 200.0, 0.3)
    zone = reply["pairs"][0]["zones"][0]
    peak = max(p["pressure"] for p in reply["pairs"][0]["points"])
    assert abs(0.5 * (zone[1] - zone[0]) / a - 1.0) < 0.02  # zone ends on nodes 0.01 apart (1.5 % of a)
    assert abs(peak / p0 - 1.0) < 0.02


def test_moment_out_of_range_is_refused(client):
    with pytest.raises(ContactError) as err:
        client.solve(scenes.punch_on_block({"flat": {"half_width": 1.0}}, load=10.0, moment=20.0))
    assert err.value.code == "incompatible_loads"
    # M = 20 is twice its bound P·b = 10; P = 10 is half of the 20 that M needs.
    assert err.value.path == "/obstacles/0/punch/rotation/load"
    moment = next(b for b in err.value.details["loads"] if b["path"] == err.value.path)
    assert moment["value"] == 20.0
    assert abs(moment["min"] + 10.0) < 1e-7 and abs(moment["max"] - 10.0) < 1e-7
    assert client.health()["solves_served"] >= 1  # still up


def test_a_rounded_punch_keeps_its_rounding_within_half_width():
    # request.profile's and docs/howto/rounded-punches.md's description of corner_radius: the flat is
    # |x| <= half_width - corner_radius (0.7), the quarter circles reach to half_width
    # (1.0). Under a light load the zone ends on the rounding, and the pressure there
    # stays bounded: halving h moves the peak by 0.3 % (measured 18.55 -> 18.60),
    # where the sharp punch's corner peak grows like h^(-1/2) (29.3 -> 41.4, 1.41).
    from contact_client import ContactError, solve_local

    def peak(corner_radius: float, h: float) -> tuple[float, list]:
        req = scenes.punch_on_block({"flat": {"half_width": 1.0, "corner_radius": corner_radius}}, load=10.0,
                                    h_min=h)
        pair = solve_local(req)["pairs"][0]
        return max(q["pressure"] for q in pair["points"]), pair["zones"]

    (rounded, zones), (finer, _) = peak(0.3, 0.02), peak(0.3, 0.01)
    assert len(zones) == 1 and 0.7 < zones[0][1] < 1.0 and zones[0][0] == pytest.approx(-zones[0][1])
    assert finer == pytest.approx(rounded, rel=0.01)
    sharp, finer_sharp = peak(0.0, 0.02)[0], peak(0.0, 0.01)[0]
    assert finer_sharp / sharp > 1.3
    with pytest.raises(ContactError) as e:
        solve_local(scenes.punch_on_block({"flat": {"half_width": 1.0, "corner_radius": 1.2}}, load=10.0))
    assert e.value.code == "invalid_geometry" and e.value.path.endswith("flat/corner_radius")
