"""The pressure map of a 3D solid's contact patch (``plot_patch``, and
``plot_pressure`` on a solid's reply), drawn with the Agg backend on the ball on a
flat solved through the service, at two load factors.

What is checkable without looking: the artists exist (the filled map, the colour
bar with the stress unit, the outline, the Hertz circle); the colour range is the
pressed points' pressure range exactly (it is set from them); the outline's
vertices lie within the pressed points' extent (a patch's faces have all their
corners pressed, and T10 midsides lie on those faces' edges: 1e-12 of the extent
for the rounding of the projection); Hertz's circle has the radius of the closed
form for four times the quarter's force (the quarter model's two roller planes
through the apex).
"""

from __future__ import annotations

import math

import pytest

from contact_client import closed_forms, plot_patch, plot_pressure, scenes


@pytest.fixture(scope="module")
def ball(client):
    req = scenes.ball_on_flat_3d(h_min=0.4)
    req["units"] = {"length": "mm", "force": "N", "stress": "MPa"}
    req["load_factors"] = [0.5, 1.0]
    return req, client.solve(req)


def _pressed_extent(solid):
    xs = [q["at"][0] for q in solid["points"] if q["in_contact"]]
    ys = [q["at"][1] for q in solid["points"] if q["in_contact"]]
    return min(xs), max(xs), min(ys), max(ys)


@pytest.mark.parametrize("step", [None, 0])
def test_the_patch_map_is_drawn_from_the_points(ball, step):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    req, reply = ball
    assert reply["status"] == "solved"
    solid = reply["solid"] if step is None else reply["steps"][step]["solid"]
    ax = plot_patch(reply, request=req, reference=True, step=step)
    try:
        (mesh,) = [c for c in ax.collections if c.get_array() is not None]
        pressed = [q["pressure"] for q in solid["points"] if q["in_contact"]]
        assert mesh.get_clim() == (min(pressed), max(pressed))
        (bar,) = [a for a in ax.figure.axes if a is not ax]
        assert bar.get_ylabel() == "contact pressure [MPa]"
        assert ax.get_xlabel() == "x [mm]" and ax.get_ylabel() == "y [mm]"
        x0, x1, y0, y1 = _pressed_extent(solid)
        slack = 1e-12 * max(x1 - x0, y1 - y0)
        outline = [ln for ln in ax.lines if ln.get_color() == "k" and ln.get_linestyle() == "-"]
        assert len(outline) == sum(len(p["outline"]) for p in solid["patches"]) >= 1
        for ln in outline:
            assert all(x0 - slack <= x <= x1 + slack for x in ln.get_xdata())
            assert all(y0 - slack <= y <= y1 + slack for y in ln.get_ydata())
        # Hertz's circle around the apex, for the whole ball's load.
        (circle,) = [ln for ln in ax.lines if ln.get_label().startswith("Hertz")]
        m = req["solid"]["body"]["material"]
        load = 4.0 * solid["resultant"]["force"][2]
        a, _ = closed_forms.hertz_sphere_reference(load, 50.0, m["youngs_modulus"], m["poisson_ratio"])
        radii = [math.hypot(x, y) for x, y in zip(circle.get_xdata(), circle.get_ydata())]
        assert max(abs(r - a) for r in radii) < 1e-12 * a
    finally:
        plt.close(ax.figure)


def test_plot_pressure_draws_a_solids_patch(ball):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    req, reply = ball
    ax = plot_pressure(reply, request=req)
    try:
        assert ax.get_aspect() == 1.0
        assert any(c.get_array() is not None for c in ax.collections), "the filled map"
        assert not [ln for ln in ax.lines if ln.get_label().startswith("Hertz")], "no reference unless asked"
    finally:
        plt.close(ax.figure)
