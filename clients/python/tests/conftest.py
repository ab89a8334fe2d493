"""Fixtures: the `contact` binary, the checked-in protocol files, and a running service.

The service is started once per session on a free loopback port
(`contact serve --listen tcp/127.0.0.1:PORT`) and stopped at the end.

Environment:
  CONTACT_BIN           path of the binary (default: <repo>/target/release/contact)
  CONTACT_REQUIRE_BIN   if "1", a missing binary or proto/ file fails the tests
                        instead of skipping them (set this in CI).
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from contact_client import Client
from contact_client.local import local_service
from support import HERTZ_EXAMPLE, PROTO, REPO, load_json, validator_for

STARTUP_TIMEOUT_S = 30.0


def _missing(what: str):
    if os.environ.get("CONTACT_REQUIRE_BIN") == "1":
        pytest.fail(f"{what} (CONTACT_REQUIRE_BIN=1)")
    pytest.skip(what)


def binary_path() -> Path:
    env = os.environ.get("CONTACT_BIN")
    return Path(env).resolve() if env else REPO / "target" / "release" / "contact"


@pytest.fixture(scope="session")
def contact_bin() -> Path:
    p = binary_path()
    if not (p.is_file() and os.access(p, os.X_OK)):
        _missing(f"contact binary not found at {p} (build it, or set CONTACT_BIN)")
    return p


@pytest.fixture(scope="session")
def proto_schemas() -> dict:
    """The checked-in schemas: {"request": ..., "reply": ..., "error": ..., "progress": ...}."""
    out = {}
    for kind in ("request", "reply", "error", "progress"):
        p = PROTO / f"{kind}.schema.json"
        if not p.is_file():
            _missing(f"{p} not found")
        out[kind] = load_json(p)
    return out


@pytest.fixture(scope="session")
def hertz_example_path() -> Path:
    if not HERTZ_EXAMPLE.is_file():
        _missing(f"{HERTZ_EXAMPLE} not found")
    return HERTZ_EXAMPLE


@pytest.fixture(scope="session")
def hertz_example(hertz_example_path) -> dict:
    return load_json(hertz_example_path)


@pytest.fixture(scope="session")
def service(contact_bin, tmp_path_factory):
    """Start `contact serve` on a free 127.0.0.1 port; yield its endpoint."""
    log = tmp_path_factory.mktemp("service") / "contact-serve.log"
    with local_service(contact_bin, STARTUP_TIMEOUT_S, log=log) as endpoint:
        yield endpoint


@pytest.fixture(scope="session")
def client(service):
    """One session shared by the tests (the module-level functions are tested separately)."""
    with Client(service, timeout=60.0) as c:
        yield c


@pytest.fixture(scope="session")
def hertz_reply(client, hertz_example) -> dict:
    """The Hertz example solved once through zenoh (shared by several tests)."""
    return client.solve(hertz_example)


@pytest.fixture(scope="session")
def proto_error_validator():
    """Validator of error.schema.json, or None while the file is not checked in
    (test_schema.py then skips or fails on its own)."""
    p = PROTO / "error.schema.json"
    return validator_for(load_json(p)) if p.is_file() else None
