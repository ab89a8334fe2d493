"""Bad requests get the right structured error, and the service survives each one.

The expected code and accepted paths of every case are in expected_errors.py.
"""

from __future__ import annotations

import json

import pytest

from contact_client import ContactError
from expected_errors import EXPECTED
from scenes_small import expected_pressure, square_block


def _good() -> dict:
    return square_block()


def _mutate(fn):
    def build() -> dict:
        req = _good()
        fn(req)
        return req
    return build


def _text(s: str):
    return lambda: s


def _good_text() -> str:
    return json.dumps(_good())


def _nan_text() -> str:
    # Strict JSON has no NaN: the literal must be refused by the JSON parser itself.
    t = _good_text()
    assert '"youngs_modulus": 200.0' in t
    return t.replace('"youngs_modulus": 200.0', '"youngs_modulus": NaN')


def _set(path: str, value):
    """Mutation setting a JSON-pointer location."""
    parts = [int(p) if p.isdigit() else p for p in path.strip("/").split("/")]

    def fn(req):
        node = req
        for p in parts[:-1]:
            node = node[p]
        node[parts[-1]] = value
    return fn


def _delete(path: str):
    parts = [int(p) if p.isdigit() else p for p in path.strip("/").split("/")]

    def fn(req):
        node = req
        for p in parts[:-1]:
            node = node[p]
        del node[parts[-1]]
    return fn


def _pulled_off(req):
    # No supports: the body is held only by the flat above it, and a traction
    # pulls it down, away from the flat: no contact pressure can balance that.
    req["bodies"][0]["supports"] = []
    req["bodies"][0]["tractions"] = [{"edges": "bottom", "traction": [0.0, -1.0]}]


def _loose_second_body(req):
    # A second body with no supports and no contact pair: nothing holds it.
    loose = json.loads(json.dumps(req["bodies"][0]))
    loose["name"] = "loose"
    loose["supports"] = []
    req["bodies"].append(loose)


# case id -> payload builder (dict, str or bytes) on the small scene
PAYLOADS = {
    "malformed_json": _text('{"version": "1", "bodies": ['),
    "not_utf8": lambda: b'{"version": "\xff\xfe"}',
    "empty_payload": _text(""),
    "nan_literal": _nan_text,
    "top_level_array": _text("[]"),
    "unknown_field_top": _mutate(_set("/frobnicate", 1)),
    "unknown_field_nested": _mutate(_set("/bodies/0/material/colour", "red")),
    "missing_bodies": _mutate(_delete("/bodies")),
    "string_for_number": _mutate(_set("/bodies/0/material/youngs_modulus", "200")),
    "unknown_method": _mutate(_set("/method", "simplex")),
    "version_99": _mutate(_set("/version", "99")),
    "youngs_modulus_zero": _mutate(_set("/bodies/0/material/youngs_modulus", 0.0)),
    "youngs_modulus_negative": _mutate(_set("/bodies/0/material/youngs_modulus", -200.0)),
    "poisson_ratio_half": _mutate(_set("/bodies/0/material/poisson_ratio", 0.5)),
    # element 1 listed clockwise: (0,-1) -> (0,0) -> (1,0) has negative signed area
    "inverted_triangle": _mutate(_set("/bodies/0/mesh/inline/elements", [[0, 1, 2], [0, 3, 2]])),
    "element_index_out_of_range": _mutate(_set("/bodies/0/mesh/inline/elements", [[0, 1, 7], [0, 2, 3]])),
    "held_by_contact_pulled_off": _mutate(_pulled_off),
    "unsupported_body_without_contact": _mutate(_loose_second_body),
    "unknown_contact_edge_set": _mutate(_set("/contacts/0/edges", "roof")),
    "unknown_support_edge_set": _mutate(_set("/bodies/0/supports/0/edges", "floor")),
    "contact_body_out_of_range": _mutate(_set("/contacts/0/body", 5)),
    "no_contacts": _mutate(_set("/contacts", [])),
    "obstacle_out_of_reach": _mutate(_set("/obstacles/0/shape/line/point", [0.0, 50.0])),
    "circle_radius_negative": _mutate(_set("/obstacles/0/shape", {"circle": {"center": [0.5, 5.0], "radius": -5.0}})),
}

assert set(PAYLOADS) == set(EXPECTED), "every case needs one payload and one expectation"


def _check_alive(client):
    """After a bad request: health answers and a good solve gives the exact answer."""
    h = client.health()
    assert h["uptime_s"] >= 0
    reply = client.solve(square_block())
    assert reply["status"] == "solved"
    # Uniform uniaxial stress: total force = E/(1-nu^2) * delta/H * W (W = 1), pushing down.
    assert reply["resultant"]["fy"] == pytest.approx(-expected_pressure(), rel=1e-9)


def test_small_scene_is_good_and_exact(client):
    """The control: the unmutated small scene solves, with the exact uniform pressure."""
    reply = client.solve(square_block())
    assert reply["status"] == "solved"
    pts = reply["pairs"][0]["points"]
    assert len(pts) == 2
    for p in pts:
        # Uniform strain is exact for T3, so the tolerance is round-off.
        assert p["pressure"] == pytest.approx(expected_pressure(), rel=1e-9)
        assert abs(p["gap"]) <= 1e-12
    assert reply["resultant"]["fy"] == pytest.approx(-expected_pressure(), rel=1e-9)


@pytest.mark.parametrize("case", list(EXPECTED))
def test_bad_request(client, proto_error_validator, case):
    code, paths = EXPECTED[case]
    payload = PAYLOADS[case]()
    with pytest.raises(ContactError) as ei:
        client.solve(payload)
    e = ei.value
    assert e.code == code, f"{case}: expected {code}, got {e.code} at {e.path!r}: {e.message}"
    assert e.path in paths, f"{case}: path {e.path!r} not in {paths} ({e.code}: {e.message})"
    assert e.message.strip(), "an error must say what is wrong"
    assert e.version == "1"
    if proto_error_validator is not None:
        proto_error_validator.validate(e.reply)
    _check_alive(client)
