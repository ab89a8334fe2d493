"""Friction in the tables, the plot and the summary, on the Cattaneo-Mindlin example
(proto/examples/friction_roller_cattaneo_mindlin.json, solved in this process): the
columns obey Coulomb's law point by point and agree with the stick zone the reply
reports; a frictionless reply has the same columns, empty."""

from __future__ import annotations

import json
import math
import re
import subprocess
from pathlib import Path

import pytest

from contact_client import Reply, solve_local, to_numpy
from contact_client.reply import POINT_COLUMNS, _fallback_summary

EXAMPLE = Path(__file__).resolve().parents[3] / "proto" / "examples" / "friction_roller_cattaneo_mindlin.json"


@pytest.fixture(scope="module")
def cattaneo() -> Reply:
    r = solve_local(json.loads(EXAMPLE.read_text()))
    assert r["status"] == "solved" and r["pairs"][0]["friction"]["stick_zones"]
    return r


def _in(x: float, zones: list) -> bool:
    return any(a <= x <= b for a, b in zones)


def test_points_carry_coulomb_state_of_every_point(cattaneo):
    cols = cattaneo.points()
    assert {"tangential_traction", "slip", "state"} <= set(POINT_COLUMNS) == set(cols)
    pair = cattaneo["pairs"][0]
    mu, fr = pair["friction"]["coefficient"], pair["friction"]
    p0 = max(cols["pressure"])
    rows = list(zip(cols["x"], cols["pressure"], cols["tangential_traction"], cols["slip"], cols["state"]))
    assert len(rows) == len(pair["points"]) > 100
    max_slip = max(abs(s) for *_, s, _ in rows)
    for x, p, t, s, state in rows:
        # Inside the cone to the round-off of the solve (the certificate's cone residual
        # is 4e-14 of the largest nodal force).
        assert abs(t) <= mu * p + 1e-12 * mu * p0, (x, t, mu * p)
        if p > 0.0 and _in(x, fr["stick_zones"]):
            assert state == "stick" and abs(s) <= 1e-12 * max_slip, (x, s)
        elif p > 0.0:
            assert _in(x, fr["slip_zones"]) and state == "slip", (x, state)
            assert abs(abs(t) - mu * p) <= 1e-12 * mu * p0, (x, t, mu * p)
        else:
            assert state == "open" and t == 0.0, (x, state, t)
    states = set(cols["state"])
    assert states == {"stick", "slip", "open"}


def test_to_numpy_and_dataframe_hold_the_same_columns(cattaneo):
    np = pytest.importorskip("numpy")
    d = to_numpy(cattaneo)[0]
    cols = cattaneo.points()
    assert np.array_equal(d["tangential_traction"], np.array(cols["tangential_traction"], dtype=float))
    assert np.array_equal(d["slip"], np.array(cols["slip"], dtype=float))
    assert list(d["state"]) == cols["state"] and d["mu"] == 0.5
    assert np.array_equal(d["stick_zones"], np.array(cattaneo["pairs"][0]["friction"]["stick_zones"]))
    pd = pytest.importorskip("pandas")
    df = cattaneo.to_dataframe()
    assert list(df.columns) == list(POINT_COLUMNS)
    assert np.array_equal(df["tangential_traction"].to_numpy(), d["tangential_traction"])
    assert (df["state"] == "stick").sum() == (d["state"] == "stick").sum() > 0
    del pd


def test_a_frictionless_reply_has_the_columns_empty(hertz_example):
    np = pytest.importorskip("numpy")
    req = dict(hertz_example)
    req["settings"] = {**req.get("settings", {}), "estimate": False}
    r = solve_local(req)
    cols = r.points()
    assert set(cols) == set(POINT_COLUMNS)
    assert all(v is None for c in ("tangential_traction", "slip", "state") for v in cols[c])
    d = to_numpy(r)[0]
    assert np.isnan(d["tangential_traction"]).all() and np.isnan(d["slip"]).all() and math.isnan(d["mu"])
    assert set(d["state"]) == {""} and d["stick_zones"].shape == (0, 2)


def _peak_shear(text: str) -> tuple[float, float]:
    m = re.search(r"shear +peak \|t\| (\S+) at x = (\S+)", text)
    assert m, text
    return float(m.group(1)), float(m.group(2))


def test_the_summary_prints_the_peak_shear_and_where(cattaneo, contact_bin):
    cols = cattaneo.points()
    k = max(range(len(cols["x"])), key=lambda i: abs(cols["tangential_traction"][i]))
    t, x = _peak_shear(repr(cattaneo))
    assert t == pytest.approx(abs(cols["tangential_traction"][k]), rel=1e-6)
    assert x == pytest.approx(cols["x"][k], rel=1e-6)
    # Cattaneo-Mindlin's peak is at the edge of the stick zone, where it meets mu p.
    assert cols["state"][k] == "slip" and t == pytest.approx(0.5 * cols["pressure"][k], rel=1e-6)
    cli = subprocess.run([str(contact_bin), "solve", str(EXAMPLE), "--summary"], capture_output=True, text=True,
                         timeout=120, check=True).stdout
    assert _peak_shear(cli) == (t, x)
    # A reply the built-in solver cannot read (a newer service's) gets the same line.
    assert _peak_shear(_fallback_summary(Reply({**cattaneo, "field_of_a_newer_service": 1}))) == (t, x)


def test_the_summary_names_the_units(cattaneo):
    req = json.loads(EXAMPLE.read_text())
    req["units"] = {"length": "mm", "force": "N", "stress": "MPa"}
    req["settings"] = {**req.get("settings", {}), "estimate": False}
    text = repr(solve_local(req))
    assert re.search(r"contact load fx \S+ N, fy \S+ N, m \S+ N·mm", text), text
    assert re.search(r"zones \[\S+, \S+\] mm; peak pressure \S+ MPa at x = \S+ mm", text), text
    assert re.search(r"shear +peak \|t\| \S+ MPa at x = \S+ mm", text), text
    assert re.search(r"friction force fx \S+ N", text), text
    fallback = _fallback_summary(solve_local(req))
    assert re.search(r"fy \S+ N, m \S+ N·mm", fallback) and re.search(r"peak pressure \S+ MPa at x = \S+ mm", fallback)
    # Without units, no names: the numbers alone, as before.
    assert " MPa" not in repr(cattaneo) and " mm" not in repr(cattaneo)


def test_plot_pressure_draws_the_shear_panel(cattaneo, tmp_path):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    np = pytest.importorskip("numpy")
    ax = pytest.importorskip("contact_client").plot_pressure(cattaneo)
    fig = ax.figure
    assert len(fig.axes) == 2
    shear = fig.axes[1]
    d = to_numpy(cattaneo)[0]
    order = np.argsort(d["x"])
    lines = {ln.get_label(): ln for ln in shear.get_lines()}
    t = lines["t, pair 0"]
    assert np.array_equal(t.get_ydata(), d["tangential_traction"][order])
    bound = next(ln for label, ln in lines.items() if label.startswith("±μp"))
    assert np.allclose(bound.get_ydata(), 0.5 * d["pressure"][order])
    # Zoomed on the zone as the pressure panel is (shared x).
    assert shear.get_xlim() == ax.get_xlim() and ax.get_xlim()[1] < 1.0
    fig.tight_layout()
    fig.savefig(tmp_path / "cattaneo.png", dpi=80)
    # shear=False, and a frictionless reply, keep the single panel.
    assert len(pytest.importorskip("contact_client").plot_pressure(cattaneo, shear=False).figure.axes) == 1
