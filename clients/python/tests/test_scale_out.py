"""Scale-out on loopback: a zenoh router (`contact router`) and two `contact serve`
instances connected to it, clients connected to the router only.

Each query is answered by exactly one instance; `spread=True` shares the load
between them; and when one instance is killed in the middle of a stream of
queries, every query is answered correctly by the survivor or gets a retryable
error (no answer, `busy`) whose retry succeeds, and no attempt outlives its
timeout.
"""

from __future__ import annotations

import json
import signal
import socket
import subprocess
import threading
import time
from dataclasses import dataclass
from pathlib import Path

import pytest

from contact_client import Client, ContactError, TransportError
from contact_client.load_test import judge, references, with_client_id, workload
from contact_client.local import free_loopback_port, stop

STARTUP_S = 30.0
QUERY_TIMEOUT_S = 10.0


@dataclass
class Fleet:
    router: str
    services: dict  # zid -> Popen
    logs: list


def _instance_of(log: Path, deadline: float) -> str:
    """The zid a `serve --log-format json` process logs at startup."""
    while time.monotonic() < deadline:
        for line in log.read_text(errors="replace").splitlines():
            try:
                rec = json.loads(line)
            except json.JSONDecodeError:
                continue
            zid = rec.get("fields", {}).get("instance")
            if zid:
                return zid
        time.sleep(0.1)
    raise AssertionError(f"no startup line in {log}:\n{log.read_text(errors='replace')[-2000:]}")


def _wait_for_listener(endpoint: str, deadline: float) -> None:
    host, port = endpoint.split("/", 1)[1].rsplit(":", 1)
    while True:
        try:
            socket.create_connection((host, int(port)), timeout=1.0).close()
            return
        except OSError:
            assert time.monotonic() < deadline, f"nothing listens on {endpoint}"
            time.sleep(0.1)


@pytest.fixture
def fleet(contact_bin, tmp_path):
    router = f"tcp/127.0.0.1:{free_loopback_port()}"
    procs, logs, files = [], [], []

    def start(name: str, *args: str) -> subprocess.Popen:
        log = tmp_path / f"{name}-{len(logs)}.log"
        logs.append(log)
        files.append(open(log, "wb"))
        p = subprocess.Popen([str(contact_bin), *args, "--log-format", "json"], stdin=subprocess.DEVNULL,
                             stdout=subprocess.DEVNULL, stderr=files[-1])
        procs.append(p)
        return p

    try:
        start("router", "router", "--listen", router)
        deadline = time.monotonic() + STARTUP_S
        _wait_for_listener(router, deadline)  # a service whose router is not up yet exits at once
        services = {}
        for name in ("a", "b"):
            p = start(name, "serve", "--connect", router, "--workers", "1")
            services[_instance_of(logs[-1], deadline)] = p
        while True:
            try:
                with Client(router) as c:
                    if c.instances(timeout=2.0) == sorted(services):
                        break
            except TransportError:
                pass
            assert time.monotonic() < deadline, "the fleet did not come up"
            time.sleep(0.2)
        yield Fleet(router, services, logs)
    finally:
        for p in procs:
            stop(p)
        for f in files:
            f.close()


def _instance(reply_or_error: dict) -> str:
    return reply_or_error["request_id"].rsplit("-", 1)[0]


def _hertz() -> bytes:
    return dict(workload())["hertz_t3"]


def test_each_query_is_answered_by_one_instance(fleet):
    n = 8
    with Client(fleet.router) as c:
        before = sum(h["solves_served"] for h in c.health_all())
        assert len(c.health_all()) == 2
        for _ in range(n):
            replies = list(c.session.get("contact/solve", payload=_hertz(), timeout=QUERY_TIMEOUT_S))
            assert len(replies) == 1 and replies[0].ok is not None
        after = sum(h["solves_served"] for h in c.health_all())
    assert after - before == n, "an instance solved a query whose answer nobody used"


def test_spread_shares_the_load(fleet):
    with Client(fleet.router, spread=True) as c:
        ids = [c.solve(_hertz())["request_id"] for _ in range(6)]
    assert {_instance({"request_id": i}) for i in ids} == set(fleet.services)
    # `--log-format json`: one JSON object per line, each reply logged under its request id.
    logged = set()
    for log in fleet.logs:
        for line in log.read_text().splitlines():
            logged.add(json.loads(line).get("fields", {}).get("request_id"))
    assert set(ids) <= logged


@pytest.mark.parametrize("spread", [False, True], ids=["zenoh_routing", "spread"])
def test_killing_an_instance_mid_stream(fleet, spread):
    work = workload()
    with Client(fleet.router) as c:
        reference = references(c, work, QUERY_TIMEOUT_S)
        victim = _instance(c.solve(_hertz())) if not spread else sorted(fleet.services)[0]
    survivor = next(z for z in fleet.services if z != victim)
    threads, per_thread = 4, 15
    kill_after = threads * per_thread // 3
    answered = 0
    killed = threading.Event()
    lock = threading.Lock()
    records = []  # (name, verdict, attempts, instance, started_after_kill, slowest attempt)

    def stream(k: int) -> None:
        nonlocal answered
        with Client(fleet.router, timeout=QUERY_TIMEOUT_S, spread=spread) as c:
            for i in range(per_thread):
                name, payload = work[(k + i) % len(work)]
                cid = f"kill-{k}-{i}"
                after_kill = killed.is_set()
                attempts, slowest = 0, 0.0
                while True:
                    attempts += 1
                    t0 = time.monotonic()
                    try:
                        got = ("ok", c.solve(with_client_id(payload, cid), retries=0))
                    except ContactError as e:
                        got = ("error", e.code, e.reply)
                    except TransportError as e:
                        got = ("lost", str(e))
                    slowest = max(slowest, time.monotonic() - t0)
                    retryable = got[0] == "lost" or (got[0] == "error" and got[1] == "busy")
                    if not retryable or attempts == 4:
                        break
                verdict = judge(reference[name], got[:2], cid)
                who = _instance(got[1] if got[0] == "ok" else got[2]) if got[0] != "lost" else None
                with lock:
                    records.append((name, verdict, attempts, who, after_kill, slowest))
                    answered += 1
                    if answered == kill_after and not killed.is_set():
                        fleet.services[victim].send_signal(signal.SIGKILL)
                        killed.set()

    workers = [threading.Thread(target=stream, args=(k,)) for k in range(threads)]
    for w in workers:
        w.start()
    for w in workers:
        w.join(timeout=threads * per_thread * QUERY_TIMEOUT_S)
    assert not any(w.is_alive() for w in workers), "a client hung"
    assert killed.is_set() and fleet.services[victim].wait(timeout=10) == -signal.SIGKILL

    assert len(records) == threads * per_thread
    wrong = [r for r in records if r[1] != "ok"]
    assert not wrong, f"wrong or unanswered after retries: {wrong}"
    assert max(r[5] for r in records) < QUERY_TIMEOUT_S + 2.0, "an attempt outlived its timeout"
    assert all(r[3] in (None, survivor) for r in records if r[4]), "a dead instance answered"
    assert sum(1 for r in records if r[4]) >= threads * per_thread // 2, "the kill was not mid-stream"
    retried = sum(1 for r in records if r[2] > 1)
    print(f"\n{len(records)} queries, {retried} retried after the kill of {victim}, all answered correctly")
    with Client(fleet.router) as c:
        assert [h["instance"] for h in c.health_all()] == [survivor]
        assert _instance(c.solve(_hertz())) == survivor
