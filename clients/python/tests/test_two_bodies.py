"""Two deformable bodies through zenoh: Hertz for two cylinders seen from both
sides, action and reaction, and the checked-in example."""

from __future__ import annotations

import json

from contact_client import closed_forms, scenes
from support import PROTO


def _peak(points):
    return max(p["pressure"] for p in points)


def test_two_cylinders_match_hertz_from_both_sides(client):
    reply = client.solve(scenes.two_cylinders())
    assert reply["status"] == "solved"
    pair = reply["pairs"][0]
    assert pair["against"] == "lower" and pair["discretization"] == "mortar"
    P = pair["resultant"]["fy"]
    a, p0 = closed_forms.hertz_two_cylinders(P, 8.0, 12.0, 200.0, 0.3, 100.0, 0.25)
    # 2 %: the zone ends are quantized by the node spacing (h/a about 2.3 %,
    # the zone ending at the last node in contact), a/R is about 0.09.
    zone = pair["zones"][0]
    assert abs(0.5 * (zone[1] - zone[0]) / a - 1.0) < 0.02
    assert abs(_peak(pair["points"]) / p0 - 1.0) < 0.02
    assert abs(_peak(pair["other_points"]) / p0 - 1.0) < 0.02
    # Action and reaction.
    other = pair["other_resultant"]
    assert abs(other["fy"] + P) <= 1e-12 * P
    for cert in reply["certificate"].values():
        assert cert <= 1e-8


def test_two_bodies_example_is_valid_and_solved(client, proto_schemas):
    import jsonschema

    req = json.loads((PROTO / "examples" / "two_bodies_cylinders.json").read_text())
    jsonschema.validate(req, proto_schemas["request"])
    reply = client.solve(req)
    jsonschema.validate(reply, proto_schemas["reply"])
    assert reply["status"] == "solved"


def test_body_held_only_by_contact_and_pulled_away_is_refused(client):
    import pytest

    from contact_client import ContactError

    req = scenes.two_cylinders()
    # The upper cylinder loses its support and is pulled up by a traction.
    req["bodies"][0]["supports"] = []
    req["bodies"][0]["tractions"] = [{"edges": "flat", "traction": [0.0, 1.0]}]
    with pytest.raises(ContactError) as err:
        client.solve(req)
    assert err.value.code == "incompatible_loads"
    assert err.value.path == "/bodies/0/tractions/0"
