"""A small run of the load test (``contact_client.load_test``) against the session's service:
concurrent clients, a mix of valid and invalid requests, nothing lost or wrong."""

from __future__ import annotations

import pytest

from contact_client import load_test
from contact_client.local import local_service


def test_concurrent_mix_is_answered_like_sequential_requests(service):
    r = load_test.run(service, clients=4, requests=12, timeout=60.0, max_seconds=120.0)
    assert r["sent"] == r["answered"] == 48
    assert (r["lost"], r["wrong"]) == (0, 0), load_test.report(r)
    assert r["valid_identical"] == r["valid_sent"] > 0
    assert 0 < r["latency_s"]["p50"] <= r["latency_s"]["p99"] <= r["latency_s"]["max"]
    assert 0 < r["refusal_latency_s"]["p50"] <= r["refusal_latency_s"]["max"]


@pytest.mark.parametrize("endpoint", ["tcp/10.0.0.1:7447", "tcp/192.168.1.2:7447", "tcp/example.org:7447"])
def test_only_loopback_endpoints_are_loaded(endpoint):
    with pytest.raises(ValueError):
        load_test.check_loopback(endpoint)


def test_loopback_endpoints_are_accepted():
    for ep in ("tcp/127.0.0.1:7447", "tcp/localhost:7447", "tcp/[::1]:7447"):
        load_test.check_loopback(ep)


def test_a_burst_from_one_session_keeps_every_limit(contact_bin):
    """The load test's burst mode, small: 16 requests at once from one session,
    twice, against one worker and a queue of two, so most are ``busy``. Every
    reply within its ``time_limit`` plus max(10 %, 0.2 s) of its sending (the
    mode's own check), and each ``busy`` within 0.2 s: a generous bound for a
    loaded 2-core machine, where they came in 1-12 ms at the median."""
    with local_service(contact_bin, extra=("--workers", "1", "--queue-limit", "2")) as endpoint:
        r = load_test.burst(endpoint, size=16, rounds=2, time_limit=2.0, timeout=60.0)
    assert (r["lost"], r["wrong"], r["late"]) == (0, 0, []), load_test.burst_report(r)
    assert r["busy"] >= 16 and r["busy"] + r["ok"] == r["sent"] == 32, load_test.burst_report(r)
    assert r["busy_latency_s"]["max"] <= 0.2, load_test.burst_report(r)
    assert r["service_busy_latency_s"]["window"] == r["busy"]
