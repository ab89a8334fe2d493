"""The client library: encoding, config, error classes, health, the module-level
functions, and transport failures kept apart from service errors."""

from __future__ import annotations

import json
import math
import time

import pytest

import contact_client
from contact_client import Client, ContactError, TransportError, client as client_mod, closed_forms, scenes
from scenes_small import expected_pressure, square_block
from support import free_loopback_port

# ---- offline: no service needed -------------------------------------------------

def test_encode_request_forms():
    req = square_block()
    as_dict = client_mod.encode_request(req)
    assert json.loads(as_dict) == req
    text = json.dumps(req)
    assert client_mod.encode_request(text) == text.encode()  # sent verbatim
    assert client_mod.encode_request(b"{x") == b"{x"
    with pytest.raises(TypeError):
        client_mod.encode_request(42)


def test_encode_refuses_non_json_floats():
    req = square_block()
    req["bodies"][0]["material"]["youngs_modulus"] = math.nan
    with pytest.raises(ValueError):
        client_mod.encode_request(req)


def test_numpy_values_anywhere_in_a_request_are_plain_json():
    np = pytest.importorskip("numpy")
    req = square_block()
    numpy_req = square_block()
    body = numpy_req["bodies"][0]
    body["material"]["youngs_modulus"] = np.float32(body["material"]["youngs_modulus"])
    body["material"]["poisson_ratio"] = np.float64(body["material"]["poisson_ratio"])
    body["mesh"]["inline"]["nodes"] = np.array(body["mesh"]["inline"]["nodes"])
    body["mesh"]["inline"]["elements"] = np.array(body["mesh"]["inline"]["elements"], dtype=np.int64)
    numpy_req["contacts"][0]["body"] = np.int32(0)
    assert json.loads(client_mod.encode_request(numpy_req)) == json.loads(client_mod.encode_request(req))
    body["mesh"]["inline"]["nodes"][0, 0] = np.nan
    with pytest.raises(ValueError):
        client_mod.encode_request(numpy_req)


def test_config_is_client_loopback_without_multicast():
    conf = client_mod.make_config("tcp/127.0.0.1:7447")
    assert json.loads(conf.get_json("mode")) == "client"
    assert json.loads(conf.get_json("connect/endpoints")) == ["tcp/127.0.0.1:7447"]
    assert json.loads(conf.get_json("scouting/multicast/enabled")) is False
    assert contact_client.DEFAULT_CONNECT.startswith("tcp/127.0.0.1:")
    with pytest.raises(ValueError):
        client_mod.make_config("127.0.0.1:7447")


def test_nobody_listening_is_a_transport_error():
    # A client-mode open against a loopback port nobody listens on fails at once.
    endpoint = f"tcp/127.0.0.1:{free_loopback_port()}"
    t0 = time.monotonic()
    with pytest.raises(TransportError) as e:
        contact_client.solve(square_block(), connect=endpoint, timeout=5.0)
    # Said in the user's terms, not in zenoh's (no Rust source paths).
    assert str(e.value) == f"no contact service answers at {endpoint}: is `contact serve` running?"
    with pytest.raises(TransportError):
        contact_client.health(connect=endpoint, timeout=5.0)
    assert time.monotonic() - t0 < 30.0


def test_error_classes_are_distinct():
    assert not issubclass(TransportError, ContactError)
    assert not issubclass(ContactError, TransportError)
    e = ContactError("invalid_material", "E must be > 0", "/bodies/0/material/youngs_modulus", version="1")
    assert (e.code, e.path, e.reply["code"]) == ("invalid_material", "/bodies/0/material/youngs_modulus",
                                                 "invalid_material")


def test_hertz_reference_closed_form():
    # One elastic body on a rigid one: E* = E / (1 - nu^2) = 200 / 0.91 = 219.78.
    # (VERIFICATION.md's reference numbers for R = 8, a = 0.9628 and p0 = 6.612,
    # use E* = 109.89, which is two equal elastic bodies; for a rigid cylinder
    # they are a = 0.6808, p0 = 9.351, the values asserted below.)
    # a = sqrt(4 P R / (pi E*)); p0 = 2P/(pi a) = sqrt(P E* / (pi R)).
    a, p0 = closed_forms.hertz_reference(10.0, 8.0, 200.0, 0.3)
    e_star = 200.0 / 0.91
    assert a == pytest.approx(math.sqrt(320.0 / (math.pi * e_star)), rel=1e-14)
    assert p0 == pytest.approx(math.sqrt(10.0 * e_star / (math.pi * 8.0)), rel=1e-12)
    assert a == pytest.approx(0.68078, rel=1e-4)
    assert p0 == pytest.approx(9.3514, rel=1e-4)
    # The load balances the elliptical pressure: integral of p over [-a, a] = pi a p0 / 2 = P.
    assert math.pi * a * p0 / 2.0 == pytest.approx(10.0, rel=1e-14)
    # Plane stress: E* = E.
    a_s, _ = closed_forms.hertz_reference(10.0, 8.0, 200.0, 0.3, "plane_stress")
    assert a_s == pytest.approx(math.sqrt(320.0 / (math.pi * 200.0)), rel=1e-14)


def test_builder_mirrors_example_structure():
    """The builder's geometry: a circle of the given radius overlapping the top face y = 0 by depth."""
    req = scenes.hertz_cylinder(radius=8.0, depth=0.2, element="t6")
    assert req["obstacles"][0]["shape"]["circle"]["radius"] == 8.0
    assert req["bodies"][0]["mesh"]["rectangle"]["element"] == "t6"
    assert req["bodies"][0]["mesh"]["rectangle"]["corner"][1] + req["bodies"][0]["mesh"]["rectangle"]["height"] == 0.0
    # Circle bottom overlaps the top face y = 0 by depth.
    c = req["obstacles"][0]["shape"]["circle"]
    assert c["center"][1] - c["radius"] == pytest.approx(-0.2)


def test_builder_defaults_are_the_example(hertz_example):
    """scenes.hertz_cylinder() mirrors the checked-in Hertz example (up to defaults
    written out, the free text, and the mesh extent, which the example sets by hand)."""
    extent = hertz_example["bodies"][0]["mesh"]["rectangle"]["grading"]["extent"]
    built = scenes.hertz_cylinder(extent=extent)

    def normal(req):
        r = json.loads(json.dumps(req))
        r.pop("description", None)
        r.setdefault("method", "auto")
        r.setdefault("analysis", "plane_strain")
        r["bodies"][0]["mesh"]["rectangle"].setdefault("element", "t3")
        return r

    assert normal(built) == normal(hertz_example)


# ---- against the service -----------------------------------------------------------

def test_health_record(client):
    h0 = client.health()
    for k in ("version", "uptime_s", "solves_served", "queue_depth", "in_flight"):
        assert k in h0, k
    # "version" is the service's own version; the protocol it speaks, when reported, is "1".
    assert isinstance(h0["version"], str) and h0["version"]
    assert h0.get("protocol", "1") == "1"
    assert h0["uptime_s"] >= 0 and h0["queue_depth"] >= 0 and h0["in_flight"] >= 0
    client.solve(square_block())
    h1 = client.health()
    assert h1["solves_served"] >= h0["solves_served"] + 1
    assert h1["uptime_s"] >= h0["uptime_s"]


def test_module_functions_open_their_own_session(service):
    reply = contact_client.solve(json.dumps(square_block()), connect=service, timeout=30.0)
    assert reply["resultant"]["fy"] == pytest.approx(-expected_pressure(), rel=1e-9)
    assert "uptime_s" in contact_client.health(connect=service)
    assert set(contact_client.schema(connect=service)) == {"request", "reply", "error", "progress"}
    with pytest.raises(ContactError) as ei:
        contact_client.solve("{", connect=service)
    assert ei.value.code == "malformed_json"


def test_client_id_is_echoed(client):
    req = square_block()
    req["client_id"] = "abc-123"
    assert client.solve(req)["client_id"] == "abc-123"
    assert "client_id" not in client.solve(square_block())


def test_zenoh_timeout_is_a_transport_error(client, hertz_example):
    # The Hertz example takes far longer than 1 ms; zenoh's own timeout answers
    # with a non-JSON error ("Timeout") or nothing, which is not a service error.
    with pytest.raises(TransportError):
        client.solve(hertz_example, timeout=0.001)
    assert "uptime_s" in client.health()


def test_unserved_key_is_a_transport_error(client):
    with pytest.raises(TransportError):
        client_mod._query(client.session, "contact/nothing_here", None, 2.0)


def test_closed_client_refuses(service):
    c = Client(service)
    c.close()
    with pytest.raises(TransportError):
        c.health()


def _uncertifiable(req: dict) -> dict:
    # A tolerance below round-off: no certificate can meet it, so the service
    # answers numerical_error (deterministically) with the numbers attached.
    return {**req, "settings": {"tolerance": 1e-30}}


def test_a_reply_that_is_not_solved_raises(client):
    from contact_client import NotSolved
    with pytest.raises(NotSolved) as ei:
        client.solve(_uncertifiable(square_block()))
    assert ei.value.code == "numerical_error"
    assert ei.value.reply["status"] == "numerical_error" and ei.value.reply["pairs"]
    # check=False hands the reply back for inspection.
    assert client.solve(_uncertifiable(square_block()), check=False)["status"] == "numerical_error"


def test_cli_exit_code_says_not_solved(contact_bin, tmp_path):
    import subprocess
    path = tmp_path / "strict.json"
    path.write_text(json.dumps(_uncertifiable(square_block())))
    cp = subprocess.run([str(contact_bin), "solve", str(path)], capture_output=True, timeout=120)
    assert cp.returncode == 3, cp.stderr
    assert json.loads(cp.stdout)["status"] == "numerical_error"


def test_the_timeout_becomes_the_time_limit():
    from contact_client.client import _with_time_limit
    # 60 s of waiting: the service is told to stop by 60·0.9 − 0.5 s.
    assert _with_time_limit({"version": "1"}, 60.0)["time_limit"] == pytest.approx(53.5)
    # A smaller limit of the request's own is kept; strings go verbatim.
    assert _with_time_limit({"time_limit": 5.0}, 60.0)["time_limit"] == 5.0
    assert _with_time_limit('{"version": "1"}', 60.0) == '{"version": "1"}'
    # Below a second there is nothing sensible to ask for.
    assert "time_limit" not in _with_time_limit({"version": "1"}, 1.0)


def test_answers_that_are_not_the_services_are_refused(hertz_reply):
    """A reply that does not validate against the reply schema, or that echoes
    another client_id, is a TransportError, not an answer; an unread refusal
    (busy) carries no client_id and passes."""
    from contact_client.client import _verify

    ours = hertz_reply.get("client_id")
    _verify("reply", dict(hertz_reply), "contact/solve", ours, True)
    forged = {"version": hertz_reply["version"], "status": "solved", "pairs": []}
    with pytest.raises(TransportError, match="does not validate"):
        _verify("reply", forged, "contact/solve", None, True)
    with pytest.raises(TransportError, match="client_id"):
        _verify("reply", {**hertz_reply, "client_id": "someone-else"}, "contact/solve", "mine", True)
    busy = {"version": hertz_reply["version"], "code": "busy", "message": "retry later", "path": ""}
    _verify("error", busy, "contact/solve", "mine", True)
    with pytest.raises(TransportError, match="client_id"):
        _verify("error", {**busy, "client_id": "someone-else"}, "contact/solve", "mine", True)


def test_tls_options_are_checked_before_connecting(tmp_path):
    pem = tmp_path / "x.pem"
    pem.write_text("-")
    with pytest.raises(ValueError, match="tls/"):
        client_mod.make_config("tcp/127.0.0.1:7447", {"ca": str(pem)})
    with pytest.raises(ValueError, match="go together"):
        client_mod.make_config("tls/127.0.0.1:7447", {"ca": str(pem), "cert": str(pem)})
    with pytest.raises(ValueError, match="keys"):
        client_mod.make_config("tls/127.0.0.1:7447", {"certificate": str(pem)})
    with pytest.raises(FileNotFoundError):
        client_mod.make_config("tls/127.0.0.1:7447", {"ca": str(tmp_path / "missing.pem")})
    conf = client_mod.make_config("tls/127.0.0.1:7447", {"ca": str(pem), "cert": str(pem), "key": str(pem)})
    assert conf.get_json("transport/link/tls/enable_mtls") == "true"
