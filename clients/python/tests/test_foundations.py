"""Footings on tensionless foundations through zenoh: Winkler exactness,
Pasternak's closed form, the half-plane roller against Hertz."""

from __future__ import annotations

import json

import pytest

from contact_client import ContactError, closed_forms, scenes
from support import PROTO


def test_winkler_footing_settles_load_over_k(client):
    reply = client.solve(scenes.footing_on_foundation({"winkler": {"stiffness": 100.0}}))
    assert reply["status"] == "solved"
    for p in reply["pairs"][0]["points"]:
        assert abs(p["pressure"] - 1.0) < 1e-8  # uniform stress is exact
    f = reply["foundations"][0]
    assert f["model"] == "winkler" and abs(f["load"] - 2.0) < 1e-12
    for x, w in zip(f["x"], f["w"]):
        assert abs(w - (0.01 if abs(x) <= 1.0 else 0.0)) < 1e-10
    assert any("translation in x" in n for n in reply["notes"])


def test_pasternak_footing_follows_the_closed_form(client):
    k, mu = 100.0, 25.0
    req = scenes.footing_on_foundation({"pasternak": {"stiffness": k, "shear": mu}}, youngs_modulus=1e6, extent=10.0)
    reply = client.solve(req)
    assert reply["status"] == "solved"
    f = reply["foundations"][0]
    w0 = closed_forms.pasternak_deflection(0.0, 2.0, 1.0, k, mu)
    for x, w in zip(f["x"], f["w"]):
        if abs(x) < 6.0:  # 1 %: the layer's cells are at most a fifth of the decay length
            assert abs(w - closed_forms.pasternak_deflection(x, 2.0, 1.0, k, mu)) < 0.01 * w0


def test_half_plane_roller_matches_hertz(client):
    req = json.loads((PROTO / "examples" / "foundation_half_plane_roller.json").read_text())
    reply = client.solve(req)
    assert reply["status"] == "solved"
    m = closed_forms.hertz_measure(reply)
    a, p0 = closed_forms.hertz_reference(m["P"], 8.0, 200.0, 0.3)
    assert abs(m["a"] / a - 1.0) < 0.01  # panels of 0.005: 0.7 % of a
    assert abs(m["p0"] / p0 - 1.0) < 0.01
    assert reply["foundations"][0]["reference_distance"] == 20.0


def test_footing_pulled_off_its_foundation_is_refused(client):
    req = scenes.footing_on_foundation({"winkler": {"stiffness": 100.0}}, pressure=-1.0)
    with pytest.raises(ContactError) as err:
        client.solve(req)
    assert err.value.code == "incompatible_loads"
    assert err.value.path == "/bodies/0/tractions/0"


@pytest.mark.parametrize("length, stress", [(1.0, 1.0), (1000.0, 1e-6)])
def test_an_upward_pull_is_reported_as_the_force_it_is_in_the_request_units(client, length, stress):
    # The same footing in m and Pa, then in mm and MPa: a pull of pressure q on the
    # top of width B is the upward force q B per unit thickness (B q: length x stress),
    # and a foundation that only pushes must carry it as a force <= 0 along +y.
    B, q = 2.0 * length, 1.0 * stress
    req = scenes.footing_on_foundation({"winkler": {"stiffness": 100.0 * stress / length}}, width=B,
                                       height=0.5 * length, pressure=-q, youngs_modulus=1000.0 * stress,
                                       size=0.05 * length, extent=5.0 * length)
    with pytest.raises(ContactError) as err:
        client.solve(req)
    e = err.value
    assert e.code == "incompatible_loads" and e.path == "/bodies/0/tractions/0"
    (load,) = e.details["loads"]
    force = q * B
    # The value is the load itself (1e-9: the request's numbers scaled in and out).
    assert load["value"] == pytest.approx(force, rel=1e-9)
    # Admissible: no upward force at all. The LP's bound is run to a gap of 1e-13 of
    # its nondimensional scale; measured 6e-11 of the pull: 1e-6 of it is loose.
    assert load.get("min") is None and abs(load["max"]) < 1e-6 * force
    assert "translation in y" in e.message and f"the load {force:g} along" in e.message
    assert "moment" not in e.message and "nondimensional" not in e.message
