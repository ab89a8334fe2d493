"""Load test of a ``contact`` service on loopback: N concurrent clients, each
sending M requests from a fixed mix of valid and invalid ones.

Every answer is checked against the answer to the same request sent alone
(sequentially, before the load): a valid request must get the identical reply
(all fields but ``timings``, ``cache``, ``request_id`` and the echoed
``client_id``, which must be the one sent), an invalid one the same error code.
A query with no structured answer within its timeout is *lost*; an answer that
differs is *wrong*; ``busy`` is retried (and counted). Bounded in count and in
time (``--max-seconds``), and loopback only::

    python -m contact_client.load_test --serve target/release/contact --clients 16 --requests 50
    python -m contact_client.load_test --connect tcp/127.0.0.1:7447 --clients 16 --requests 50

Prints throughput, latency percentiles and the counts; exits 1 when any reply
was lost or wrong. ``--only NAME`` sends one request of the mix (``hertz_t3``:
the coarse Hertz scene, for round trip and solves/s); ``--overflow`` does not
retry ``busy`` but counts those answers and their latency (with
``--serve-args "--workers 1 --queue-limit 0"`` and more clients than that,
most requests overflow)::

    python -m contact_client.load_test --serve target/release/contact --clients 4 --requests 200 --only hertz_t3
    python -m contact_client.load_test --serve target/release/contact --serve-args "--workers 1 --queue-limit 0" \
        --clients 8 --requests 50 --only hertz_t3 --overflow

``--deadline DOFS,...`` is a mode of its own: for each size, the Hertz block
meshed uniformly to about that many DOF is solved once without a limit, then
with ``time_limit`` at 30, 50, 70 and 90 % of that time; it prints how late
each answer came against max(10 % of the limit, 0.2 s), and exits 1 if any was
later (start the service with ``--cache-mb 0``, or the repeats are cache hits)::

    python -m contact_client.load_test --serve target/release/contact --serve-args "--cache-mb 0" \
        --deadline 500000,1000000,2000000

``--burst N`` is another: ``--rounds`` times (default 5), N requests sent at
once from one session (``--only``, default ``hertz_t3``), each with
``--time-limit`` (default 2 s); it prints the latency of the ``busy`` answers
and of the others, each taken from the sending of its query, and exits 1 if
any reply came later than max(10 %, 0.2 s) past the time limit, any ``busy``
later than ``--busy-within`` (default 5 ms), or any was lost or wrong (with
``--serve-args "--workers 1 --queue-limit 4"`` most of a burst of 32 is
``busy``)::

    python -m contact_client.load_test --serve target/release/contact --serve-args "--workers 1 --queue-limit 4" \
        --burst 32 --rounds 10

``--router`` puts a ``contact router`` between the clients and the service
(plain TCP), ``--tls`` the production configuration instead: the router on a
mutual-TLS endpoint with deploy/router-acl.json5, the instance and the clients
with certificates made for the run (``contact_client.secure``; needs the
``cryptography`` package). Same mix, same checks::

    python -m contact_client.load_test --serve target/release/contact --tls --clients 16 --requests 50

Length: one command-line tool, this docstring (a tenth of the file) its manual; its
modes (the mix, ``--deadline``, ``--burst``, through ``--router`` or ``--tls``) share
the workload, the judging of answers against the references sent alone and the
start-up of the service, so they stay together.
"""

from __future__ import annotations

import argparse
import functools
import ipaddress
import json
import math
import socket
import sys
import tempfile
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass, field

import zenoh

from . import scenes
from .client import KEY_SOLVE, Client, ContactError, TransportError
from .local import local_service

#: Reply fields that legitimately differ between two answers to one request.
VOLATILE = ("timings", "cache", "request_id", "client_id")


def workload() -> list[tuple[str, bytes]]:
    """(name, payload) of the mix: 6 valid scenes and 6 invalid requests."""

    def hertz(**kw) -> dict:
        return scenes.hertz_cylinder(h_min=0.05, **kw)

    bad_material = hertz()
    bad_material["bodies"][0]["material"]["poisson_ratio"] = 0.5
    unknown_field = hertz()
    unknown_field["bodies"][0]["colour"] = "red"
    cut = hertz()
    cut["time_limit"] = 1e-6  # meshing alone takes longer: certainly a timeout
    valid = {
        "hertz_fine": scenes.hertz_cylinder(),
        "hertz_t3": hertz(),
        "hertz_t6_shallow": hertz(depth=0.08, element="t6"),
        "hertz_penalty": hertz(depth=0.1) | {"method": "penalty"},
        "flat_punch": scenes.punch_on_block({"flat": {"half_width": 1.0}}, load=10.0, h_min=0.05),
        "circle_punch": scenes.punch_on_block({"circle": {"radius": 8.0}}, load=10.0, h_min=0.05),
    }
    invalid = {
        "malformed_json": b'{"version": "1", "bodies": [',
        "not_utf8": b'{"version": "\xff\xfe"}',
        "bad_material": bad_material,
        "unsupported_version": hertz() | {"version": "99"},
        "unknown_field": unknown_field,
        "timeout": cut,
    }
    enc = lambda r: r if isinstance(r, bytes) else json.dumps(r).encode()  # noqa: E731
    return [(k, enc(v)) for k, v in (valid | invalid).items()]


def with_client_id(payload: bytes, client_id: str) -> bytes:
    """The payload with ``client_id`` set (left as is when it is not a JSON object)."""
    try:
        req = json.loads(payload)
    except (UnicodeDecodeError, json.JSONDecodeError):
        return payload
    return json.dumps(req | {"client_id": client_id}).encode()


def outcome(client: Client, payload: bytes, timeout: float, retries: int = 20) -> tuple[str, object]:
    """("ok", reply) | ("error", code) | ("lost", reason), after retrying ``busy`` ``retries`` times."""
    try:
        return "ok", client.solve(payload, timeout=timeout, retries=retries)
    except ContactError as e:
        return "error", e.code
    except TransportError as e:
        return "lost", str(e)


def stable(reply: dict) -> dict:
    out = {k: v for k, v in reply.items() if k not in VOLATILE}
    # The factorization-time prediction follows the service's measured rate,
    # which every finished factorization updates: a diagnostic, not the answer.
    if isinstance(out.get("diagnostics"), dict):
        out["diagnostics"] = {k: v for k, v in out["diagnostics"].items() if k != "factorization_predicted"}
    return out


def references(client: Client, work: list[tuple[str, bytes]], timeout: float) -> dict[str, tuple[str, object]]:
    """Each request of the mix answered alone: what every later answer must equal."""
    out = {}
    for name, payload in work:
        kind, value = outcome(client, payload, timeout)
        if kind == "lost":
            raise TransportError(f"reference answer to {name} lost: {value}")
        out[name] = (kind, stable(value) if kind == "ok" else value)
    return out


def judge(expected: tuple[str, object], got: tuple[str, object], client_id: str) -> str:
    """'ok', 'wrong' or 'lost' for one answer."""
    kind, value = got
    if kind == "lost":
        return "lost"
    if got == ("error", "busy") and expected != got:
        return "busy"
    if kind != expected[0]:
        return "wrong"
    if kind == "ok":
        return "ok" if value.get("client_id") == client_id and stable(value) == expected[1] else "wrong"
    return "ok" if value == expected[1] else "wrong"


@dataclass
class Tally:
    counts: dict = field(default_factory=lambda: {"ok": 0, "wrong": 0, "lost": 0, "busy": 0})
    latencies: list = field(default_factory=list)
    #: Latencies of the `busy` answers (not retried with ``overflow``).
    busy_latencies: list = field(default_factory=list)
    #: Latencies of the refusals alone (invalid requests): answered on arrival,
    #: they must not wait behind the solves.
    refusal_latencies: list = field(default_factory=list)
    valid_identical: int = 0
    notes: list = field(default_factory=list)
    lock: threading.Lock = field(default_factory=threading.Lock)

    def add(self, verdict: str, latency: float, name: str, expected: tuple[str, object], detail: str) -> None:
        expected_kind = expected[0]
        with self.lock:
            self.counts[verdict] += 1
            if verdict == "busy":
                self.busy_latencies.append(latency)
                return
            self.latencies.append(latency)
            # A `timeout` is valid work that queues and runs out of time; every
            # other error of the mix is a refusal on arrival.
            if expected_kind == "error" and expected[1] != "timeout":
                self.refusal_latencies.append(latency)
            if verdict == "ok" and expected_kind == "ok":
                self.valid_identical += 1
            if verdict != "ok" and len(self.notes) < 20:
                self.notes.append(f"{verdict}: {name}: {detail[:300]}")


def percentile(sorted_values: list[float], p: float) -> float:
    """Nearest rank, as the service's health does."""
    if not sorted_values:
        return 0.0
    return sorted_values[min(len(sorted_values), max(1, math.ceil(p * len(sorted_values)))) - 1]


def run(connect: str, clients: int = 16, requests: int = 50, timeout: float = 60.0,
        max_seconds: float = 600.0, spread: bool = False, only: str | None = None,
        overflow: bool = False, tls: dict | None = None) -> dict:
    """The load test against a running service; returns the figures (see ``report``)."""
    check_loopback(connect)
    work = workload()
    if only is not None:
        work = [(k, v) for k, v in work if k == only]
        if not work:
            raise ValueError(f"no request {only!r} in the mix")
    with Client(connect, timeout=timeout, tls=tls) as c:
        reference = references(c, work, timeout)
    tally = Tally()
    stop_at = time.monotonic() + max_seconds
    barrier = threading.Barrier(clients)

    def one_client(k: int) -> None:
        # judge() compares every answer with the reference field by field, which
        # subsumes the schema check; that check's ~14 ms per 59 kB reply under the
        # GIL would otherwise measure the clients, not the service.
        with Client(connect, timeout=timeout, spread=spread, verify=False, tls=tls) as c:
            barrier.wait()
            for i in range(requests):
                if time.monotonic() > stop_at:
                    return
                name, payload = work[(k + i) % len(work)]
                cid = f"load-{k}-{i}"
                t0 = time.perf_counter()
                got = outcome(c, with_client_id(payload, cid), timeout, retries=0 if overflow else 20)
                verdict = judge(reference[name], got, cid)
                tally.add(verdict, time.perf_counter() - t0, name, reference[name], repr(got[1]))

    threads = [threading.Thread(target=one_client, args=(k,), daemon=True) for k in range(clients)]
    t0 = time.perf_counter()
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=max(0.0, stop_at - time.monotonic()) + timeout + 5.0)
    wall = time.perf_counter() - t0
    lat = sorted(tally.latencies)
    refusals = sorted(tally.refusal_latencies)
    busy = sorted(tally.busy_latencies)
    sent = clients * requests
    answered = sum(tally.counts.values())
    return {
        "clients": clients,
        "requests_per_client": requests,
        "sent": sent,
        "answered": answered,
        # A query never attempted (time bound hit) or still hanging is lost too.
        "lost": tally.counts["lost"] + (sent - answered),
        "wrong": tally.counts["wrong"],
        "ok": tally.counts["ok"],
        "busy": tally.counts["busy"],
        # Valid requests answered identically to the sequential answer, per second.
        "solves_per_s": tally.valid_identical / wall if wall > 0 else 0.0,
        "valid_identical": tally.valid_identical,
        "valid_sent": sum(1 for k in range(clients) for i in range(requests)
                          if reference[work[(k + i) % len(work)][0]][0] == "ok"),
        "wall_s": wall,
        "throughput_per_s": answered / wall if wall > 0 else 0.0,
        "latency_s": {"p50": percentile(lat, 0.50), "p90": percentile(lat, 0.90),
                      "p99": percentile(lat, 0.99), "max": lat[-1] if lat else 0.0},
        "busy_latency_s": {"p50": percentile(busy, 0.50), "p90": percentile(busy, 0.90),
                           "max": busy[-1] if busy else 0.0},
        "refusal_latency_s": {"p50": percentile(refusals, 0.50), "p90": percentile(refusals, 0.90),
                              "max": refusals[-1] if refusals else 0.0},
        "notes": tally.notes,
    }


def report(r: dict) -> str:
    lat = r["latency_s"]
    ref = r["refusal_latency_s"]
    busy = r["busy_latency_s"]
    lines = [
        f"clients x requests : {r['clients']} x {r['requests_per_client']} = {r['sent']}",
        f"wall time          : {r['wall_s']:.2f} s",
        f"throughput         : {r['throughput_per_s']:.1f} replies/s, {r['solves_per_s']:.1f} valid solves/s",
        f"latency            : p50 {lat['p50'] * 1e3:.1f} ms, p90 {lat['p90'] * 1e3:.1f} ms, "
        f"p99 {lat['p99'] * 1e3:.1f} ms, max {lat['max'] * 1e3:.1f} ms",
        f"refusals (invalid) : p50 {ref['p50'] * 1e3:.1f} ms, p90 {ref['p90'] * 1e3:.1f} ms, "
        f"max {ref['max'] * 1e3:.1f} ms",
        f"busy (not retried) : {r['busy']}: p50 {busy['p50'] * 1e3:.1f} ms, p90 {busy['p90'] * 1e3:.1f} ms, "
        f"max {busy['max'] * 1e3:.1f} ms",
        f"answered correctly : {r['ok']}",
        f"valid, identical to the sequential answer: {r['valid_identical']} of {r['valid_sent']}",
        f"lost               : {r['lost']}",
        f"wrong              : {r['wrong']}",
    ]
    return "\n".join(lines + [f"  {n}" for n in r["notes"]])


def uniform_hertz(dofs: int, time_limit: float | None = None) -> dict:
    """The Hertz block (40 x 20) meshed uniformly with about ``dofs`` DOF (2 per node)."""
    req = scenes.hertz_cylinder()
    m = req["bodies"][0]["mesh"]["rectangle"]
    m.pop("grading", None)
    m["size"] = math.sqrt(40.0 * 20.0 * 2.0 / dofs)
    if time_limit is not None:
        req["time_limit"] = time_limit
    return req


def deadlines(connect: str, sizes: list[int], timeout: float = 600.0, tls: dict | None = None) -> bool:
    """The --deadline mode: True when every answer came within max(10 % of its limit, 0.2 s)."""
    check_loopback(connect)
    ok = True
    with Client(connect, timeout=timeout, tls=tls) as c:
        for dofs in sizes:
            t = time.perf_counter()
            reply = c.solve(uniform_hertz(dofs), timeout=timeout, retries=0)
            full = time.perf_counter() - t
            print(f"{reply['size']['dofs']} DOF: {full:.2f} s without a limit")
            for frac in (0.3, 0.5, 0.7, 0.9):
                limit = round(frac * full, 2)
                t = time.perf_counter()
                try:
                    c.solve(uniform_hertz(dofs, limit), timeout=timeout, retries=0)
                    got = "solved"
                except ContactError as e:
                    got = e.code
                late = time.perf_counter() - t - limit
                within = late <= allowed_lateness(limit)
                ok &= within
                print(f"  limit {limit:.2f} s: {got}, {late:+.3f} s past it ({'within' if within else 'NOT within'} "
                      f"max(10 %, 0.2 s))")
    return ok


def allowed_lateness(limit: float) -> float:
    """How late past its time limit a reply may come: max(10 % of the limit, 0.2 s)."""
    return max(0.1 * limit, 0.2)


def burst(connect: str, size: int = 32, rounds: int = 5, only: str = "hertz_t3", time_limit: float = 2.0,
          timeout: float = 60.0, tls: dict | None = None, busy_within: float = 0.005) -> dict:
    """The --burst mode: ``rounds`` times, ``size`` requests sent at once from ONE
    session (zenoh delivers one session's queries through one link, in order),
    each with ``time_limit``; a round starts when the last one ended.

    Every reply's latency is taken from just before its query was sent to the
    moment it arrives (a callback on zenoh's receiving thread: the replies are
    not read in the order sent, so a quick ``busy`` is not timed behind the
    solves sent before it). Figures: the ``busy`` latencies, the others', and
    the deadline check: each reply within ``time_limit`` + max(10 %, 0.2 s)
    of its sending, and each ``busy`` within ``busy_within`` seconds of it
    (``busy_late``). ``ok`` replies must equal the one to the same request sent
    alone without the limit (``judge``), unless their ``notes`` say the limit
    cut a part (the estimate's companion solve); ``timeout`` is an answer."""
    check_loopback(connect)
    if size < 1 or rounds < 1:
        raise ValueError("burst size and rounds must be positive")
    work = dict(workload())
    if only not in work:
        raise ValueError(f"no request {only!r} in the mix")
    request = json.loads(work[only]) | {"time_limit": time_limit}
    allowed = time_limit + allowed_lateness(time_limit)
    tally = Tally()
    late = []
    all_latencies = []
    timeouts = cut = 0
    with Client(connect, timeout=timeout, tls=tls) as c:
        # Without the limit: under it, the same request may be solved or cut
        # (`timeout` is an answer too); solved, it must be this answer.
        reference = references(c, [(only, work[only])], timeout)[only]
        session = c.session
        for r in range(rounds):
            bodies = [json.dumps(request | {"client_id": f"burst-{r}-{k}"}).encode() for k in range(size)]
            sent = [0.0] * size
            first: list = [None] * size
            ended = threading.Semaphore(0)
            lock = threading.Lock()

            def on_reply(reply, k, first=first, lock=lock):
                now = time.perf_counter()
                with lock:
                    if first[k] is None:
                        ok = reply.ok
                        first[k] = (now, ok is not None, (ok or reply.err).payload.to_bytes())

            handlers = [zenoh.handlers.Callback(functools.partial(on_reply, k=k), ended.release, indirect=False)
                        for k in range(size)]
            # The reply callbacks need the interpreter lock this loop holds; at
            # the default switch interval (5 ms) they waited for it in steps of
            # 5 ms, which timed the client, not the service.
            switch = sys.getswitchinterval()
            sys.setswitchinterval(1e-5)
            try:
                for k in range(size):
                    sent[k] = time.perf_counter()
                    session.get(KEY_SOLVE, handlers[k], payload=bodies[k], timeout=timeout,
                                consolidation=zenoh.ConsolidationMode.NONE)
            finally:
                sys.setswitchinterval(switch)
            for _ in range(size):
                ended.acquire(timeout=timeout + 5.0)
            for k in range(size):
                cid = f"burst-{r}-{k}"
                if first[k] is None:
                    tally.add("lost", timeout, only, reference, "no reply")
                    continue
                at, ok, raw = first[k]
                latency = at - sent[k]
                got = decoded(ok, raw)
                # A part cut by the limit (the estimate's companion solve) is
                # said in `notes`: that answer is not compared with the whole one.
                was_cut = got[0] == "ok" and any("time limit" in n for n in got[1].get("notes") or [])
                timeouts += got == ("error", "timeout")
                cut += was_cut
                verdict = "ok" if got == ("error", "timeout") or was_cut else judge(reference, got, cid)
                tally.add(verdict, latency, only, reference, repr(got[1])[:300])
                all_latencies.append(latency)
                if latency > allowed:
                    late.append((cid, got[1] if got[0] == "error" else "solved", latency))
        # The service's own figure: from a query's arrival to its `busy` handed
        # to zenoh, without the link and this client (None: an older service).
        service_busy = c.health().get("busy_latency_s")
    lat = sorted(tally.latencies)
    busy = sorted(tally.busy_latencies)
    sent_n = size * rounds
    return {
        "size": size,
        "rounds": rounds,
        "sent": sent_n,
        "time_limit_s": time_limit,
        "allowed_s": allowed,
        "lost": tally.counts["lost"],
        "wrong": tally.counts["wrong"],
        "ok": tally.counts["ok"],
        "busy": tally.counts["busy"],
        "timeouts": timeouts,
        "cut": cut,
        "late": late,
        "max_latency_s": max(all_latencies, default=0.0),
        "latency_s": {"p50": percentile(lat, 0.50), "p99": percentile(lat, 0.99), "max": lat[-1] if lat else 0.0},
        "busy_latency_s": {"p50": percentile(busy, 0.50), "p99": percentile(busy, 0.99),
                           "max": busy[-1] if busy else 0.0},
        "busy_within_s": busy_within,
        "busy_late": sum(x > busy_within for x in busy),
        "service_busy_latency_s": service_busy,
        "notes": tally.notes,
    }


def decoded(ok: bool, raw: bytes) -> tuple[str, object]:
    """A raw answer as ``outcome`` gives it: ("ok", reply) | ("error", code) | ("lost", reason)."""
    try:
        value = json.loads(raw)
    except (UnicodeDecodeError, json.JSONDecodeError):
        return "lost", raw[:200]
    if ok:
        return "ok", value
    if isinstance(value, dict) and isinstance(value.get("code"), str):
        return "error", value["code"]
    return "lost", raw[:200]


def burst_report(r: dict) -> str:
    busy, lat = r["busy_latency_s"], r["latency_s"]
    lines = [
        f"burst x rounds     : {r['size']} x {r['rounds']} = {r['sent']} from one session, "
        f"time_limit {r['time_limit_s']} s",
        f"busy               : {r['busy']}: p50 {busy['p50'] * 1e3:.1f} ms, p99 {busy['p99'] * 1e3:.1f} ms, "
        f"max {busy['max'] * 1e3:.1f} ms; {r['busy_late']} later than {r['busy_within_s'] * 1e3:g} ms",
    ]
    sb = r.get("service_busy_latency_s")
    if sb:
        lines.append(f"busy, in service   : {sb['window']}: p50 {sb['p50'] * 1e3:.3f} ms, "
                     f"p99 {sb['p99'] * 1e3:.3f} ms, "
                     f"max {sb['max'] * 1e3:.3f} ms (arrival to reply handed to zenoh)")
    lines += [
        f"other replies      : {r['ok']} ({r['timeouts']} timeout, {r['cut']} with a part cut): "
        f"p50 {lat['p50'] * 1e3:.1f} ms, p99 {lat['p99'] * 1e3:.1f} ms, "
        f"max {lat['max'] * 1e3:.1f} ms",
        f"deadline           : {len(r['late'])} of {r['sent']} later than {r['allowed_s']:.3f} s after sending "
        f"(slowest {r['max_latency_s']:.3f} s)",
        f"lost               : {r['lost']}",
        f"wrong              : {r['wrong']}",
    ]
    lines += [f"  late: {cid}: {what} after {s:.3f} s" for cid, what, s in r["late"][:20]]
    return "\n".join(lines + [f"  {n}" for n in r["notes"]])


def check_loopback(connect: str) -> None:
    """Refuse any endpoint but a loopback address: this tool only loads the local machine."""
    try:
        host = connect.split("/", 1)[1].rsplit(":", 1)[0].strip("[]")
        addr = ipaddress.ip_address(socket.gethostbyname(host) if host == "localhost" else host)
    except (IndexError, ValueError, OSError) as e:
        raise ValueError(f"cannot read a loopback address from {connect!r}") from e
    if not addr.is_loopback:
        raise ValueError(f"{connect!r} is not a loopback endpoint; the load test only targets this machine")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m contact_client.load_test", description=__doc__.split("\n\n")[0])
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--connect", help="endpoint of a running service (loopback only), e.g. tcp/127.0.0.1:7447")
    where.add_argument("--serve", metavar="BINARY", help="start `BINARY serve` on a free loopback port for the test")
    p.add_argument("--deadline", metavar="DOFS", help="time-limit mode: comma-separated sizes, e.g. 500000,1000000")
    p.add_argument("--burst", type=int, metavar="N",
                   help="burst mode: N requests at once from one session (--only, default hertz_t3), --rounds times")
    p.add_argument("--rounds", type=int, default=5, help="bursts sent one after the other (default 5)")
    p.add_argument("--busy-within", type=float, default=5.0, metavar="MS",
                   help="with --burst: fail when a busy answer takes longer than this (default 5 ms)")
    p.add_argument("--time-limit", type=float, default=2.0,
                   help="with --burst: every request's time_limit in seconds (default 2)")
    p.add_argument("--clients", type=int, default=16, help="concurrent clients (default 16)")
    p.add_argument("--requests", type=int, default=50, help="requests per client (default 50)")
    p.add_argument("--timeout", type=float, default=60.0, help="per-query timeout in seconds (default 60)")
    p.add_argument("--max-seconds", type=float, default=600.0, help="stop sending after this (default 600)")
    p.add_argument("--spread", action="store_true", help="spread queries over all live instances")
    p.add_argument("--only", metavar="NAME", help="send only this request of the mix (e.g. hertz_t3)")
    p.add_argument("--overflow", action="store_true", help="do not retry busy; count it and its latency")
    p.add_argument("--serve-args", default="", help="extra arguments of `BINARY serve` (with --serve)")
    p.add_argument("--router", action="store_true", help="with --serve: through a `BINARY router` (plain TCP)")
    p.add_argument("--tls", action="store_true",
                   help="with --serve: through a router on mutual TLS with deploy/router-acl.json5")
    a = p.parse_args(argv)
    if (a.router or a.tls) and not a.serve:
        p.error("--router and --tls start their own router and service: use them with --serve")
    if a.clients < 1 or a.requests < 1 or a.clients * a.requests > 100_000:
        p.error("--clients and --requests must be positive, at most 100000 queries in all")
    if a.deadline:
        sizes = [int(x) for x in a.deadline.split(",")]
        if a.serve:
            with started(a) as (endpoint, tls):
                return 0 if deadlines(endpoint, sizes, a.timeout, tls) else 1
        return 0 if deadlines(a.connect, sizes, a.timeout) else 1
    if a.burst is not None:
        if a.burst < 1 or a.rounds < 1 or a.burst * a.rounds > 100_000 or not a.time_limit > 0 \
                or not a.busy_within > 0:
            p.error("--burst and --rounds must be positive, at most 100000 queries in all; --time-limit and "
                    "--busy-within positive")
        kw = dict(size=a.burst, rounds=a.rounds, only=a.only or "hertz_t3", time_limit=a.time_limit, timeout=a.timeout,
                  busy_within=a.busy_within * 1e-3)
        if a.serve:
            with started(a) as (endpoint, tls):
                r = burst(endpoint, tls=tls, **kw)
        else:
            r = burst(a.connect, **kw)
        print(burst_report(r))
        return 1 if r["lost"] or r["wrong"] or r["late"] or r["busy_late"] else 0
    if a.serve:
        with started(a) as (endpoint, tls):
            r = run(endpoint, a.clients, a.requests, a.timeout, a.max_seconds, a.spread, a.only, a.overflow, tls)
    else:
        r = run(a.connect, a.clients, a.requests, a.timeout, a.max_seconds, a.spread, a.only, a.overflow)
    print(report(r))
    return 1 if r["lost"] or r["wrong"] else 0


@contextmanager
def started(a: argparse.Namespace):
    """The service of ``--serve``, alone or behind a router (``--router``, ``--tls``):
    yields (endpoint, the clients' tls)."""
    extra = tuple(a.serve_args.split())
    if not (a.router or a.tls):
        with local_service(a.serve, extra=extra) as endpoint:
            yield endpoint, None
        return
    from .secure import routed_service

    # Nested: one `with (...)` over both needs CPython 3.10, and the package supports 3.9.
    with tempfile.TemporaryDirectory(prefix="contact-load-") as d:  # noqa: SIM117
        with routed_service(a.serve, d, tls=a.tls, serve_args=extra) as (endpoint, tls, _):
            yield endpoint, tls


if __name__ == "__main__":
    sys.exit(main())
