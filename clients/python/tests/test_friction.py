"""Coulomb friction from the builders: Cattaneo-Mindlin's stick zone (a roller on a rigid
floor, two identical cylinders), full sliding, and a punch pushed sideways below and
beyond mu P (Fichera's condition with friction)."""

from __future__ import annotations

import math

import pytest

from contact_client import ContactError, closed_forms, scenes

MU = 0.5


def _stick_half_width(points: list[dict]) -> float:
    """Half the length of the run of sticking points, its ends midway between the run's
    end points and their outer neighbours (the true transition lies there to half a
    spacing), as the Rust test measures it."""
    pts = sorted(points, key=lambda p: p["x"])
    idx = [i for i, p in enumerate(pts) if p["state"] == "stick"]
    assert idx and idx == list(range(idx[0], idx[-1] + 1)), "one contiguous stick zone"
    lo, hi = idx[0], idx[-1]
    left = 0.5 * (pts[lo]["x"] + pts[lo - 1]["x"]) if lo > 0 else pts[lo]["x"]
    right = 0.5 * (pts[hi]["x"] + pts[hi + 1]["x"]) if hi + 1 < len(pts) else pts[hi]["x"]
    return 0.5 * (right - left)


def test_roller_stick_zone_follows_cattaneo_mindlin(client):
    # The roller of the Rust test (crates/contact/tests/friction.rs): nu = 0.499 so
    # that the coupling of an elastic body on a rigid floor (Dundurs beta = 0.001) is
    # negligible, T6 (P2-P0, no locking), h = 0.0075 at the zone (half a spacing is at
    # most 1.3 % of c). Tolerance 2 % on c, as there; a from Hertz with the reply's P.
    nu, radius, e = 0.499, 8.0, 200.0
    req = scenes.roller_on_floor(radius=radius, poisson_ratio=nu, element="t6", h_min=0.0075, extent=0.6,
                                 friction=MU, shifts=[0.015, 0.025, 0.035])
    r = client.solve(req)
    assert r["status"] == "solved"
    steps = r["steps"]
    assert len(steps) == 13, "pressed in 10 steps (the default), then 3 shifts"
    for k, st in enumerate(steps[10:], start=1):
        p, q = st["resultant"]["fy"], -st["resultant"]["fx"]
        assert 0.25 < q / (MU * p) < 0.75, f"step {k}: Q/muP = {q / (MU * p)}"
        a, _ = closed_forms.hertz_reference(p, radius, e, nu)
        c = _stick_half_width(st["pairs"][0]["points"])
        expect = closed_forms.cattaneo_mindlin_stick(a, q, MU, p)
        assert c == pytest.approx(expect, rel=0.02), f"step {k}: Q/muP = {q / (MU * p)}"
        # The peak shear, at the stick zone's edge, against mu p0 sqrt(Q/(mu P)) (p0 from Hertz with the
        # reply's P). Pressed in ten steps (the default) it reads +4.2, +4.2, +4.0 % at Q/muP = 0.29, 0.49,
        # 0.67; pressed in one step +15.5, +8.3, +5.1 %: closing nodes carried their open motion into the
        # step's slip. The 4 % left is the finite roller (a/R = 0.062; +1.6 to +2.6 % at a/R = 0.04, docs
        # verification/friction.md), hence 5 %.
        a, p0 = closed_forms.hertz_reference(p, radius, e, nu)
        peak = max(abs(pt["tangential_traction"] or 0.0) for pt in st["pairs"][0]["points"])
        assert peak == pytest.approx(MU * p0 * math.sqrt(q / (MU * p)), rel=0.05), f"step {k}"


def test_roller_moved_far_slides_with_mu_p(client):
    # Moved 0.06 sideways after pressing (beyond the stick range), every point in
    # contact slips with |t| = mu p, to the round-off of the step's LU (1e-9 of mu p0),
    # and Q = mu P.
    r = client.solve(scenes.roller_on_floor(h_min=0.01, friction=MU, shifts=[0.06]))
    assert r["status"] == "solved"
    pair = r["pairs"][0]
    touching = [p for p in pair["points"] if p["state"] != "open"]
    assert len(touching) > 40
    p0 = max(p["pressure"] for p in pair["points"])
    for p in touching:
        assert p["state"] == "slip"
        assert abs(abs(p["tangential_traction"]) - MU * p["pressure"]) <= 1e-9 * MU * p0
    assert pair["friction"]["stick_zones"] == []
    assert -r["resultant"]["fx"] == pytest.approx(MU * r["resultant"]["fy"], rel=1e-9)
    assert "friction" in repr(r) and f"μ {MU}" in repr(r), "the summary shows the friction"


def test_punch_pushed_below_mu_p_is_in_equilibrium(client):
    # P = 10 then Q = 0.5 mu P: the punch sticks, and its equilibrium makes the friction
    # forces on the block add up to Q (1e-8 of P: the step is solved by LU).
    mu, load = 0.3, 10.0
    q = 0.5 * mu * load
    r = client.solve(scenes.punch_on_block({"flat": {"half_width": 1.0}}, load=load, horizontal_load=q,
                                           h_min=0.05, friction=mu))
    assert r["status"] == "solved"
    fr = r["pairs"][0]["friction"]
    assert fr["tangential_resultant"]["fx"] == pytest.approx(q, abs=1e-8 * load)
    punch = r["punches"][0]
    assert punch["p1"] == pytest.approx(q, abs=1e-8 * load) and punch["unique"]
    assert fr["stick_zones"], "part of the face sticks"


def test_punch_pushed_beyond_mu_p_is_refused_with_its_range(client):
    mu, load = 0.3, 10.0
    q = 1.05 * mu * load
    with pytest.raises(ContactError) as err:
        client.solve(scenes.punch_on_block({"flat": {"half_width": 1.0}}, load=load, horizontal_load=q,
                                           h_min=0.05, friction=mu))
    assert err.value.code == "incompatible_loads"
    assert err.value.path == "/obstacles/0/punch/horizontal/load"
    bound = next(b for b in err.value.details["loads"] if b["path"] == err.value.path)
    # The LP's range is exactly +-mu P on a flat face, found to its 1e-13 gap (1e-8 here).
    assert bound["min"] == pytest.approx(-mu * load, rel=1e-8)
    assert bound["max"] == pytest.approx(mu * load, rel=1e-8)


def test_two_cylinders_stick_zone_follows_cattaneo_mindlin(client):
    # Two identical cylinders (R = 8, E = 200, nu = 0.3: the same material, so Dundurs
    # beta = 0 and Cattaneo-Mindlin holds at nu = 0.3), T6, h = 0.007 at the contact (half
    # a spacing is at most 1.2 % of c), as crates/contact/tests/friction_two_bodies.rs.
    # Tolerance 2 % on c; a from Hertz for two cylinders with the reply's P. Each body's
    # contact force, friction included, is minus the other's (round-off: 1e-12 of P).
    radius, e, nu = 8.0, 200.0, 0.3
    req = scenes.two_cylinders(R1=radius, R2=radius, E1=e, E2=e, nu1=nu, nu2=nu, element="t6", h_min=0.007,
                               friction=MU, shifts=[0.02, 0.035])
    r = client.solve(req)
    assert r["status"] == "solved"
    steps = r["steps"]
    assert len(steps) == 12, "pressed in 10 steps (the default), then 2 shifts"
    assert steps[9]["pairs"][0]["friction"]["slip_zones"] == [], "nothing slips under P alone (beta = 0)"
    for k, st in enumerate(steps[10:], start=1):
        pair = st["pairs"][0]
        p, q = st["resultant"]["fy"], -st["resultant"]["fx"]
        assert 0.25 < q / (MU * p) < 0.75, f"step {k}: Q/muP = {q / (MU * p)}"
        a, _ = closed_forms.hertz_two_cylinders(p, radius, radius, e, nu, e, nu)
        c = _stick_half_width(pair["points"])
        expect = closed_forms.cattaneo_mindlin_stick(a, q, MU, p)
        assert c == pytest.approx(expect, rel=0.02), f"step {k}: Q/muP = {q / (MU * p)}"
        other = pair["other_resultant"]
        assert other["fx"] == pytest.approx(-pair["resultant"]["fx"], abs=1e-12 * p)
        assert other["fy"] == pytest.approx(-pair["resultant"]["fy"], abs=1e-12 * p)
        assert all(len(pt["tangent"]) == 2 for pt in pair["points"]), "two-body friction points carry their tangent"


def test_roller_pushed_through_its_axle_follows_cattaneo_mindlin(client):
    # The pushed roller as a user first writes it: roller_on_plate with its defaults (T3,
    # h_min = 0.01 at the contact, a/R = 0.038) and the same material on both sides (Dundurs
    # beta = 0), pressed by P = 1 through its axle in ten steps (the default), then pushed
    # through it by Q = 0.3, 0.5, 0.7 muP, its rotation held. The stick zone is
    # Cattaneo-Mindlin's c within 2 % (stick_measure's ends are placed to half a spacing,
    # 0.005 to 0.0065 on the two meshes, at most 4 % of c = 0.165 at Q/muP = 0.7 and 2.5 % at
    # 0.3; measured +0.09, -0.14, -1.06 %), P and Q are carried exactly (equilibrium,
    # 1e-9), and the axle's reported force is the loads given with its rotation 0. Freed
    # (its rotation a load of 0), the same axle rolls and the reply says so.
    radius, e, nu, p = 8.0, 200.0, 0.3, 1.0
    ratios = [0.3, 0.5, 0.7]
    req = scenes.roller_on_plate(radius, e, nu, plate_modulus=e, plate_poisson=nu, load=p,
                                 tangential=[r * MU * p for r in ratios], friction=MU)
    r = client.solve(req)
    assert r["status"] == "solved"
    assert len(r["steps"]) == 13, "pressed in 10 steps (the default), then 3 pushes"
    for ratio, st in zip(ratios, r["steps"][10:]):
        m = closed_forms.stick_measure(st)
        assert m["P"] == pytest.approx(p, rel=1e-9) and m["Q"] == pytest.approx(ratio * MU * p, rel=1e-9)
        a, _ = closed_forms.hertz_two_cylinders(m["P"], radius, math.inf, e, nu, e, nu)
        expect = closed_forms.cattaneo_mindlin_stick(a, m["Q"], MU, m["P"])
        assert m["c"] == pytest.approx(expect, rel=0.02), f"Q/muP = {ratio}"
        axle = st["couplings"][0]
        assert axle["fy"] == pytest.approx(-p, rel=1e-9) and axle["fx"] == pytest.approx(m["Q"], rel=1e-9)
        assert axle["theta"] == 0.0
    assert all(w["code"] != "rolling" for w in r.get("warnings", []))
    req["bodies"][0]["couplings"][0]["rotation"] = {"load": 0.0}
    rolled = client.solve(req)
    codes = {w["code"]: w["location"] for w in rolled.get("warnings", [])}
    assert codes.get("rolling") == "/bodies/0/couplings/0/rotation", codes


def test_shifts_need_displacement_control():
    with pytest.raises(ValueError):
        scenes.roller_on_floor(load=5.0, friction=MU, shifts=[0.01])
    with pytest.raises(ValueError):
        scenes.two_cylinders(friction=MU, shifts=[])
    for steps in (0, 2.5, True):
        with pytest.raises(ValueError, match="steps"):
            scenes.roller_on_floor(friction=MU, shifts=[0.01], steps=steps)
    assert math.isclose(closed_forms.cattaneo_mindlin_stick(1.0, 0.75, 1.0, 1.0), 0.5)
    with pytest.raises(ValueError, match="needs friction"):
        scenes.roller_on_plate(load=1.0, tangential=0.1)


def test_frictional_builders_press_in_ten_steps_then_shift():
    # The press ramps by 0.1 with the shift held at 0, then each shift in turn; steps=1 is the
    # one-step path the builders made before (the press at factor 1, which a step need not name).
    roller = scenes.roller_on_floor(friction=MU, shifts=[0.01, 0.02])["load_path"]
    press, shift = "/bodies/0/supports/0", "/bodies/0/supports/1"
    assert [s["loads"].get(press, 1.0) for s in roller] == pytest.approx([k / 10 for k in range(1, 11)] + [1.0, 1.0])
    assert [s["loads"][shift] for s in roller] == [0.0] * 10 + [0.01, 0.02]
    assert scenes.roller_on_floor(friction=MU, shifts=[0.01], steps=1)["load_path"] == [
        {"loads": {shift: 0.0}}, {"loads": {shift: 0.01}}]
    assert len(scenes.two_cylinders(friction=MU, shifts=[0.02], steps=4)["load_path"]) == 5
    punch = scenes.punch_on_block({"flat": {"half_width": 1.0}}, horizontal_load=1.0, friction=0.3)["load_path"]
    assert [s["loads"].get("/obstacles/0/punch/vertical", 1.0) for s in punch] == pytest.approx(
        [k / 10 for k in range(1, 11)] + [1.0])
    assert [s["loads"]["/obstacles/0/punch/horizontal"] for s in punch] == [0.0] * 10 + [1.0]
    # The roller on a plate pushed through its axle: the coupling's vertical load ramped, its
    # horizontal one (load 1, scaled by each step) held at 0, then each tangential force.
    plate = scenes.roller_on_plate(load=2.0, tangential=[0.3, 0.6], friction=MU)
    axle = plate["bodies"][0]["couplings"][0]
    assert axle["vertical"] == {"load": -2.0} and axle["horizontal"] == {"load": 1.0} and "rotation" not in axle
    press, push = "/bodies/0/couplings/0/vertical", "/bodies/0/couplings/0/horizontal"
    path = plate["load_path"]
    assert [s["loads"].get(press, 1.0) for s in path] == pytest.approx([k / 10 for k in range(1, 11)] + [1.0] * 2)
    assert [s["loads"][push] for s in path] == [0.0] * 10 + [0.3, 0.6]
    assert len(scenes.roller_on_plate(load=2.0, friction=MU, steps=4)["load_path"]) == 4
