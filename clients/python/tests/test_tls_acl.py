"""The production configuration on loopback: a `contact router` on a mutual-TLS
endpoint with deploy/router-acl.json5, one `contact serve` holding a solver
certificate and clients holding client certificates, all made here at test
time by one CA.

The attacks of issue 37 fail under it:

* impersonation: a session with a certificate of the CA that is not a solver's
  (a client's) declares a complete queryable on ``contact/solve`` before the
  service joins; the router denies the declaration, so it receives no query and
  every solve is answered by the service;
* eavesdropping: a subscriber on ``contact/progress/**`` whose certificate is
  neither a solver's nor a client's receives nothing while a client receives
  its progress;
* a session without a certificate, or with one of another CA, cannot connect.

The service and router come from contact_client.secure (also the benchmarks' set-up).
"""

from __future__ import annotations

import threading
import time

import pytest
import zenoh

from contact_client import Client, TransportError, make_config
from contact_client.secure import CLIENT_CN, ThrowawayCA, routed_service
from support import REPO

pytest.importorskip("cryptography")

ACL = REPO / "deploy" / "router-acl.json5"
SOLVES = 3


@pytest.fixture(scope="module")
def secured(contact_bin, tmp_path_factory):
    """Router (mTLS, ACL); a rogue queryable on contact/solve with a client
    certificate, declared before the service joins; then the service.

    Yields (endpoint, {name: tls}, the payloads the rogue received)."""
    directory = tmp_path_factory.mktemp("secured")
    received: list[bytes] = []
    lock = threading.Lock()
    held = {}

    def forge(query):
        with lock:
            received.append(query.payload.to_bytes() if query.payload is not None else b"")
        query.reply("contact/solve", b'{"version": "1", "status": "solved", "pairs": []}')

    def rogue(endpoint, ca):
        held["ca"] = ca
        held["session"] = zenoh.open(make_config(endpoint, ca.issue(CLIENT_CN)))
        held["queryable"] = held["session"].declare_queryable("contact/solve", forge, complete=True)

    with routed_service(contact_bin, directory, acl=ACL, serve_args=("--workers", "1"),
                        before_serve=rogue) as (endpoint, client_tls, ca):
        try:
            certs = {"client": client_tls, "observer": ca.issue("contact-observer"),
                     "stranger": ThrowawayCA(directory, "stranger-ca").issue(CLIENT_CN)}
            yield endpoint, certs, received
        finally:
            held["queryable"].undeclare()
            held["session"].close()


def test_solves_go_through_mtls_and_the_acl(secured, hertz_example):
    endpoint, certs, _ = secured
    with Client(endpoint, timeout=60.0, tls=certs["client"]) as c:
        for k in range(SOLVES):
            reply = c.solve({**hertz_example, "client_id": f"tls-{k}"})
            assert reply["status"] == "solved" and reply["client_id"] == f"tls-{k}"
            assert reply["pairs"] and reply["pairs"][0]["points"]
        assert c.health()["solves_served"] >= SOLVES
        assert "reply" in c.schema()
        assert len(c.instances()) == 1
        assert len(c.health_all()) == 1
    # Through the instance's own key, as scale-out's spread=True sends it.
    with Client(endpoint, timeout=60.0, tls=certs["client"], spread=True) as c:
        assert c.solve({**hertz_example, "client_id": "tls-spread"})["client_id"] == "tls-spread"
        assert c._solve_key().startswith("contact/instance/")


def test_a_rogue_without_a_solver_certificate_gets_no_query(secured, hertz_example):
    endpoint, certs, received = secured
    with Client(endpoint, timeout=60.0, tls=certs["client"]) as c:
        for k in range(SOLVES):
            assert c.solve({**hertz_example, "client_id": f"rogue-{k}"})["pairs"][0]["points"]
    assert received == [], f"the rogue queryable received {len(received)} queries"


def test_a_session_without_a_client_certificate_is_refused(secured):
    endpoint, certs, _ = secured
    for tls in ({"ca": certs["client"]["ca"]}, certs["stranger"]):
        with pytest.raises(TransportError):
            Client(endpoint, timeout=5.0, tls=tls)


def test_a_subscriber_without_rights_receives_no_progress(secured, hertz_example):
    endpoint, certs, _ = secured
    overheard: list[bytes] = []
    observer = zenoh.open(make_config(endpoint, certs["observer"]))
    try:
        sub = observer.declare_subscriber("contact/progress/**", lambda s: overheard.append(s.payload.to_bytes()))
        own: list[dict] = []
        with Client(endpoint, timeout=60.0, tls=certs["client"]) as c:
            c.solve({**hertz_example, "client_id": "progress-0"}, progress=own.append)
        time.sleep(0.3)
        sub.undeclare()
    finally:
        observer.close()
    assert own, "the client itself received no progress: the test proves nothing"
    assert overheard == []
