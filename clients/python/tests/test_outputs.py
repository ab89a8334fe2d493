"""Results out: the VTU grid (read back with meshio), to_numpy and plot_pressure."""

from __future__ import annotations

import copy

import pytest

from contact_client import plot_pressure, save_vtu, scenes, to_numpy

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def hertz_vtu_reply(client, hertz_example):
    req = copy.deepcopy(hertz_example)
    req["outputs"] = ["vtu"]
    return client.solve(req)


def test_vtu_opens_with_meshio_and_holds_the_named_fields(hertz_vtu_reply, tmp_path):
    meshio = pytest.importorskip("meshio")
    r = hertz_vtu_reply
    assert "bodies" not in r, "only what outputs lists comes back"
    path = tmp_path / "hertz.vtu"
    save_vtu(r, str(path))
    m = meshio.read(path)
    n = len(m.points)
    assert m.point_data["displacement"].shape == (n, 3)
    assert abs(m.points[:, 2]).max() == 0.0 and abs(m.point_data["displacement"][:, 2]).max() == 0.0
    # The pressure field is the reply's, node by node: same maximum, zero off the candidates.
    p = m.point_data["contact_pressure"]
    pts = r["pairs"][0]["points"]
    assert p.max() == max(q["pressure"] for q in pts)
    assert (p != 0).sum() <= len(pts)
    for q in pts[:: max(1, len(pts) // 20)]:
        assert p[q["node"]] == q["pressure"]
        assert tuple(m.points[q["node"], :2]) == (q["x"], q["y"])
    stress = m.cell_data["stress"][0]
    assert stress.shape == (len(m.cells[0].data), 3)
    # Under the indenter the block is in compression: sigma_yy < 0 somewhere, of the order of p0.
    assert stress[:, 1].min() < -0.5 * p.max()
    assert set(m.cell_data["body"][0].ravel().tolist()) == {0}
    # The named tensor (XX, YY, ZZ, XY, YZ, XZ) carries plane strain's
    # sigma_zz = nu (sigma_xx + sigma_yy); von Mises and the principal stresses
    # follow from it (ParaView needs no calculator).
    import numpy as np

    t = m.cell_data["stress_tensor"][0]
    assert t.shape == (len(stress), 6)
    assert np.allclose(t[:, [0, 1, 3]], stress) and np.allclose(t[:, 2], 0.3 * (stress[:, 0] + stress[:, 1]))
    xx, yy, zz, xy = t[:, 0], t[:, 1], t[:, 2], t[:, 3]
    vm = np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3 * xy ** 2)
    assert np.allclose(m.cell_data["von_mises"][0].ravel(), vm)
    pr = m.cell_data["principal_stress"][0]
    assert np.all(pr[:, 0] >= pr[:, 1]) and np.all(pr[:, 1] >= pr[:, 2])
    assert np.allclose(pr.sum(axis=1), xx + yy + zz)
    # The top face sinks under the cylinder: the largest downward displacement is the indentation depth.
    uy = m.point_data["displacement"][:, 1]
    depth = 0.12
    assert -uy.min() == pytest.approx(depth, rel=1e-6)


def test_to_numpy_gives_the_pairs_forces_and_zones(hertz_reply):
    np = pytest.importorskip("numpy")
    (d,) = to_numpy(hertz_reply)
    assert d["body"] == "block" and d["obstacle"] == "cylinder"
    assert len(d["x"]) == len(d["pressure"]) == len(d["node"]) == hertz_reply["size"]["candidates"]
    # The nodal forces against the outward normal add up to the pair's resultant.
    fy = -(d["force"] * d["normal"][:, 1]).sum()
    assert fy == pytest.approx(hertz_reply["pairs"][0]["resultant"]["fy"], rel=1e-9)
    assert d["zones"].shape == (1, 2)
    inside = (d["x"] >= d["zones"][0, 0]) & (d["x"] <= d["zones"][0, 1])
    assert np.all(d["pressure"][~inside] <= 1e-9 * d["pressure"].max())
    # The block's top is flat: the zone along it is the same interval, its
    # length along the surface that along x.
    assert d["zones_along"].shape == (1, 2) and d["zone_ends"].shape == (1, 2, 2)
    assert sorted(d["zone_ends"][0, :, 0]) == list(d["zones"][0])
    s0, s1 = d["zones_along"][0]
    assert s1 - s0 == pytest.approx(d["zones"][0, 1] - d["zones"][0, 0], rel=1e-12)


def test_plot_pressure_draws_the_pressures_and_the_hertz_overlay(hertz_reply, hertz_example, tmp_path):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    ax = plot_pressure(hertz_reply, reference="hertz", request=hertz_example)
    data, ref = ax.lines[1], ax.lines[-1]  # lines[0]: the p = 0 axis
    assert max(data.get_ydata()) == max(p["pressure"] for p in hertz_reply["pairs"][0]["points"])
    m = scenes.hertz_measure(hertz_reply)
    _, p0 = scenes.hertz_reference(m["P"], 8.0, 200.0, 0.3)
    assert max(ref.get_ydata()) == pytest.approx(p0, rel=1e-4)
    out = tmp_path / "p.png"
    ax.figure.savefig(out)
    assert out.read_bytes()[:8] == PNG_MAGIC
    with pytest.raises(ValueError):
        plot_pressure(dict(hertz_reply), reference="hertz")  # a plain dict does not know its request


def test_plot_labels_carry_the_request_units_and_read_in_grey_scale(tmp_path):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    from contact_client import solve_local

    req = scenes.hertz_cylinder(h_min=0.04)
    req["units"] = {"length": "mm", "force": "N", "stress": "MPa"}
    reply = solve_local(req)
    assert reply["units"] == req["units"], "the reply echoes the request's units"
    ax = plot_pressure(reply, reference="hertz", request=req)
    assert ax.get_xlabel() == "x [mm]" and ax.get_ylabel() == "contact pressure [MPa]"
    assert ax.get_title().replace("\n", " ") == req["description"]
    fe, ref = ax.lines[1], ax.lines[-1]
    # Told apart without colour: markers and a solid line against a dashed one.
    assert fe.get_marker() not in (None, "None", "") and fe.get_linestyle() == "-"
    assert ref.get_linestyle() == "--" and ref.get_marker() in (None, "None", "")


def _agg():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")


def test_a_body_of_revolution_is_plotted_against_r_with_the_3d_hertz_overlay():
    _agg()
    from contact_client import solve_local

    P = 7.7
    reply = solve_local(scenes.ball_on_flat(load=P, h_min=0.03))
    ax = plot_pressure(reply, reference=True)  # the Reply knows its request
    assert ax.get_xlabel() == "r"
    _, p0 = scenes.hertz_sphere_reference(P, 10.0, 200.0, 0.3)
    ref = ax.lines[-1]
    assert ref.get_label().startswith("Hertz, sphere")
    assert max(ref.get_ydata()) == pytest.approx(p0, rel=1e-3)  # 801 samples over 1.5 a: the peak at r = 0
    # The zone [0, a] is a small part of the 10-long arc: zoomed to [0, 1.5 a].
    lo, hi = ax.get_xlim()
    zone = reply["pairs"][0]["zones"][0]
    assert lo == pytest.approx(0.0, abs=1e-12) and hi == pytest.approx(1.5 * zone[1], rel=1e-9)


def test_a_narrow_zone_is_zoomed_on_and_a_wide_one_is_not():
    _agg()
    from contact_client import solve_local

    narrow = solve_local(scenes.roller_on_floor(load=5.0, h_min=0.02))
    (z0, z1), = narrow["pairs"][0]["zones"]
    ax = plot_pressure(narrow)
    assert ax.get_xlabel() == "x"
    w = z1 - z0
    assert ax.get_xlim() == pytest.approx((z0 - 0.5 * w, z1 + 0.5 * w), rel=1e-9)
    whole = plot_pressure(narrow, zoom=False).get_xlim()
    assert whole[1] - whole[0] > 16.0, "the whole arc, 2 R = 16 wide"
    # A block held by contact touches along its whole bottom: nothing to zoom on.
    wide = solve_local(scenes.block_held_by_contact())
    lo, hi = plot_pressure(wide).get_xlim()
    assert lo <= -1.0 and hi >= 1.0


@pytest.mark.parametrize("build, closed_form", [
    (lambda: scenes.roller_on_floor(load=5.0, h_min=0.02),
     lambda P: scenes.hertz_reference(P, 8.0, 200.0, 0.3)[1]),
    (lambda: scenes.roller_on_plate(load=1.0, h_min=0.02),
     lambda P: scenes.hertz_two_cylinders(P, 8.0, float("inf"), 200.0, 0.3, 70.0, 0.33)[1]),
    (lambda: scenes.hertz_cylinder(load=10.0, h_min=0.02),
     lambda P: scenes.hertz_reference(P, 8.0, 200.0, 0.3)[1]),
])
def test_the_closed_form_overlay_is_hertz_for_the_scene_and_its_load(build, closed_form):
    _agg()
    from contact_client import solve_local

    reply = solve_local(build())
    P = abs(reply["pairs"][0]["resultant"]["fy"])
    ref = plot_pressure(reply, reference="hertz").lines[-1]
    # The overlay's peak is p0 of the scene's closed form (801 samples over twice the
    # zone: the sample nearest the centre is within 1e-5 a of it).
    assert max(ref.get_ydata()) == pytest.approx(closed_form(P), rel=1e-6)
    # And it agrees with the solver's peak as the load-control tests measure it.
    assert max(ref.get_ydata()) == pytest.approx(max(p["pressure"] for p in reply["pairs"][0]["points"]), rel=0.03)


def test_a_flat_punch_overlay_is_sadowsky_and_a_foundation_has_none():
    _agg()
    from contact_client import request as rq, solve_local

    reply = solve_local(scenes.punch_on_block({"flat": {"half_width": 1.0}}, load=10.0, h_min=0.02))
    ref = plot_pressure(reply, reference=True).lines[-1]
    assert ref.get_label().startswith("Sadowsky")
    x = ref.get_xdata()
    inside = abs(x) < 0.5
    assert ref.get_ydata()[inside] == pytest.approx([scenes.sadowsky_pressure(v, 10.0, 1.0) for v in x[inside]])
    with pytest.raises(ValueError, match="Sadowsky"):
        plot_pressure(reply, reference="hertz")
    footing = solve_local(scenes.footing_on_foundation(rq.winkler(100.0)))
    with pytest.raises(ValueError, match="callable"):
        plot_pressure(footing, reference=True)


def test_the_described_pressure_ends_at_the_fitted_edge_and_carries_the_load(hertz_reply):
    """The field `accuracy.pressure_l2` is the error of: the nodal values at the nodes, p
    falling to 0 at each zone's fitted edge (within a facet of the last node in contact,
    either side), 0 beyond; its integral along the flat surface is the pair's load to
    within the estimated pressure error (the nodal forces are its integrals against the
    shape functions, so the two differ only by the interpolation's error)."""
    np = pytest.importorskip("numpy")
    from contact_client import described_pressure

    pair = hertz_reply["pairs"][0]
    x, y, p = described_pressure(pair)
    (zone,) = pair["zones_along"]
    fitted = [f for f in zone["fitted"] if f is not None]
    assert fitted, "a Hertz zone has smooth edges"
    mid = 0.5 * (zone["start"][0] + zone["end"][0])
    xs = sorted(q["x"] for q in pair["points"])
    past = set()
    for f, end in zip(zone["fitted"], (zone["start"], zone["end"])):
        if f is None:
            continue
        # Within a facet of the zone's end node: the node before or the next one.
        i = xs.index(end[0])
        assert xs[max(i - 1, 0)] <= f["x"] <= xs[min(i + 1, len(xs) - 1)]
        outside = (x - f["x"]) * (mid - f["x"]) < 0
        assert np.all(p[outside] == 0.0)
        if (end[0] - f["x"]) * (mid - f["x"]) < 0:
            past.add((end[0], end[1]))
    for q in pair["points"]:
        at = np.flatnonzero((x == q["x"]) & (y == q["y"]))
        # An end node past its fitted edge reads 0 in the described field.
        expected = 0.0 if (q["x"], q["y"]) in past else q["pressure"]
        assert at.size and p[at[0]] == expected
    load = np.trapezoid(p, x) if hasattr(np, "trapezoid") else np.trapz(p, x)
    est = pair["accuracy"]["pressure_l2"]
    assert load == pytest.approx(abs(pair["resultant"]["fy"]), rel=max(2 * est, 1e-3))
