"""The solver built into the package: in-process replies are the service's."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from contact_client import Client, ContactError, TransportError, solve_local
from scenes_small import expected_pressure, square_block
from support import diff_replies

# The same solver on the same input: only the summation order of a parallel
# reduction could differ, far below this.
PARITY_REL = 1e-12


def test_in_process_reply_equals_the_service_reply(hertz_example, hertz_reply):
    local = solve_local(hertz_example)
    assert "request_id" not in local and "request_id" in hertz_reply
    # The service scales its factorization-time prediction by this machine's
    # measured rate; the in-process solver keeps the uncalibrated model.
    served = json.loads(json.dumps(hertz_reply))
    local = json.loads(json.dumps(local))
    for reply in (served, local):
        reply.get("diagnostics", {}).pop("factorization_predicted", None)
    diffs = diff_replies(served, local, rel=PARITY_REL, skip=("timings", "cache", "request_id"))
    assert not diffs, "\n".join(diffs[:20])


@pytest.mark.parametrize("mutation", ["poisson_ratio_half", "unknown_field", "malformed"])
def test_in_process_refusal_equals_the_service_refusal(client, mutation):
    req = square_block()
    if mutation == "poisson_ratio_half":
        req["bodies"][0]["material"]["poisson_ratio"] = 0.5
    elif mutation == "unknown_field":
        req["bodies"][0]["colour"] = "red"
    payload = json.dumps(req) if mutation != "malformed" else '{"version": "1", "bodies": ['
    with pytest.raises(ContactError) as remote:
        client.solve(payload)
    with pytest.raises(ContactError) as local:
        solve_local(payload)
    assert (local.value.code, local.value.path, str(local.value)) == (
        remote.value.code, remote.value.path, str(remote.value))


def test_local_client_solves_without_a_service():
    with Client(local=True) as c:
        reply = c.solve(square_block())
        for p in reply["pairs"][0]["points"]:
            assert p["pressure"] == pytest.approx(expected_pressure(), rel=1e-10)
        # In process, progress comes from the solver's own sink, as the service's does.
        seen = []
        c.solve(square_block(), progress=seen.append)
        # The error estimate's companion solve (the default) is the last stage.
        assert seen[0]["stage"] == "mesh" and seen[-1]["stage"] == "estimate"
        with pytest.raises(TransportError):
            c.health()


def test_numpy_requests_solve_in_process():
    np = pytest.importorskip("numpy")
    req = square_block()
    req["bodies"][0]["mesh"]["inline"]["nodes"] = np.array(req["bodies"][0]["mesh"]["inline"]["nodes"])
    req["bodies"][0]["material"]["youngs_modulus"] = np.float32(200.0)
    reply = solve_local(req)
    assert reply["pairs"][0]["points"][0]["pressure"] == pytest.approx(expected_pressure(), rel=1e-10)


def test_the_packaged_contact_command_runs_in_process(hertz_example_path):
    cp = subprocess.run([sys.executable, "-m", "contact_client._cli", "solve", str(hertz_example_path), "--summary"],
                        capture_output=True, timeout=120)
    assert cp.returncode == 0, cp.stderr.decode(errors="replace")
    assert cp.stdout.decode().splitlines()[0].split() == ["status", "solved"]


def test_point_load_and_partial_pressure_are_carried_with_their_moments():
    # A 2 x 1 block held only by the rigid floor y = 0: the floor carries each
    # load and its moment exactly (equilibrium of the discrete problem).
    from contact_client import request as rq

    def on_floor(**loads):
        block = rq.body("block", rq.material(1000.0, 0.25), rq.rectangle([-1.0, 0.0], 2.0, 1.0, 0.05), **loads)
        return rq.request([block], [rq.obstacle("floor", rq.line([0.0, 0.0], [0.0, 1.0]))],
                          [rq.contact("block", "bottom", obstacle="floor")])

    r = solve_local(on_floor(point_loads=[rq.point_load("top", [0.237, 1.0], [0.0, -3.0])]))
    assert r["resultant"]["fy"] == pytest.approx(3.0, rel=1e-9)
    assert r["resultant"]["m"] == pytest.approx(3.0 * 0.237, rel=1e-9)
    q, a, b = 2.0, -0.33, 0.71
    r = solve_local(on_floor(tractions=[rq.pressure("top", q, x_range=[a, b])]))
    assert r["resultant"]["fy"] == pytest.approx(q * (b - a), rel=1e-9)
    assert r["resultant"]["m"] == pytest.approx(q * (b * b - a * a) / 2.0, rel=1e-9)
