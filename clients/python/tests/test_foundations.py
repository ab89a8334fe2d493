"""Footings on tensionless foundations through zenoh: Winkler exactness,
Pasternak's closed form, the half-plane roller against Hertz."""

from __future__ import annotations

import json

import pytest

from contact_client import ContactError, scenes

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
    w0 = scenes.pasternak_deflection(0.0, 2.0, 1.0, k, mu)
    for x, w in zip(f["x"], f["w"]):
        if abs(x) < 6.0:  # 1 %: the layer's cells are at most a fifth of the decay length
            assert abs(w - scenes.pasternak_deflection(x, 2.0, 1.0, k, mu)) < 0.01 * w0


def test_half_plane_roller_matches_hertz(client):
    req = json.loads((PROTO / "examples" / "foundation_half_plane_roller.json").read_text())
    reply = client.solve(req)
    assert reply["status"] == "solved"
    m = scenes.hertz_measure(reply)
    a, p0 = scenes.hertz_reference(m["P"], 8.0, 200.0, 0.3)
    assert abs(m["a"] / a - 1.0) < 0.01  # panels of 0.005: 0.7 % of a
    assert abs(m["p0"] / p0 - 1.0) < 0.01
    assert reply["foundations"][0]["reference_distance"] == 20.0


def test_footing_pulled_off_its_foundation_is_refused(client):
    req = scenes.footing_on_foundation({"winkler": {"stiffness": 100.0}}, pressure=-1.0)
    with pytest.raises(ContactError) as err:
        client.solve(req)
    assert err.value.code == "incompatible_loads"
    assert err.value.path == "/bodies/0/tractions"
