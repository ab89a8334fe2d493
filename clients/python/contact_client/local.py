"""A `contact serve` process on a free loopback port, for the tests and the load test."""

from __future__ import annotations

import socket
import subprocess
import time
from contextlib import contextmanager
from pathlib import Path

from .client import Client, ContactError, TransportError


def free_loopback_port() -> int:
    """A TCP port on 127.0.0.1 that nobody listens on right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def stop(proc: subprocess.Popen, grace_s: float = 10.0) -> None:
    """SIGTERM, then SIGKILL if it has not exited within ``grace_s``."""
    if proc.poll() is None:
        proc.terminate()
    try:
        proc.wait(timeout=grace_s)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait(timeout=grace_s)


@contextmanager
def local_service(binary, startup_s: float = 30.0, extra: tuple[str, ...] = (), log: Path | None = None):
    """``binary serve`` on a free 127.0.0.1 port until the block ends; yields its endpoint
    once ``contact/health`` answers. Output goes to ``log`` (discarded without one)."""
    endpoint = f"tcp/127.0.0.1:{free_loopback_port()}"
    out = open(log, "wb") if log else subprocess.DEVNULL
    proc = subprocess.Popen([str(binary), "serve", "--listen", endpoint, *extra], stdin=subprocess.DEVNULL,
                            stdout=out, stderr=subprocess.STDOUT)

    def tail() -> str:
        return Path(log).read_text(errors="replace")[-4000:] if log else ""

    try:
        deadline = time.monotonic() + startup_s
        last = None
        while True:
            if proc.poll() is not None:
                raise RuntimeError(f"`{binary} serve` exited with {proc.returncode} during startup:\n{tail()}")
            try:
                # A client-mode open fails at once while nobody listens: retry until it answers.
                with Client(endpoint) as c:
                    c.health(timeout=2.0)
                break
            except (TransportError, ContactError) as e:
                last = e
            if time.monotonic() > deadline:
                raise RuntimeError(f"service on {endpoint} did not answer contact/health within {startup_s} s "
                                   f"(last: {last}):\n{tail()}")
            time.sleep(0.2)
        yield endpoint
    finally:
        stop(proc)
        if log:
            out.close()
