"""Command line: ``python -m contact_client solve FILE [--connect EP]`` and ``health``.

``solve`` prints the reply JSON; on a structured error it prints the error JSON
to stdout and exits 1. A transport failure (nothing answered, zenoh timeout)
is reported on stderr with exit code 2.
"""

from __future__ import annotations

import argparse
import json
import os
import sys

from .client import DEFAULT_CONNECT, Client, ContactError, TransportError


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m contact_client",
                                description="Client of the contact solve service (zenoh).")
    sub = p.add_subparsers(dest="command", required=True)

    ps = sub.add_parser("solve", help="send a request file to contact/solve and print the reply")
    ps.add_argument("file", help="request JSON file ('-' for stdin); sent verbatim")
    ps.add_argument("--connect", default=DEFAULT_CONNECT, help=f"zenoh endpoint (default {DEFAULT_CONNECT})")
    ps.add_argument("--timeout", type=float, default=60.0, help="query timeout in seconds (default 60)")

    ph = sub.add_parser("health", help="print the service's health record")
    ph.add_argument("--connect", default=DEFAULT_CONNECT, help=f"zenoh endpoint (default {DEFAULT_CONNECT})")
    ph.add_argument("--timeout", type=float, default=10.0, help="query timeout in seconds (default 10)")

    pc = sub.add_parser("schema", help="print the service's JSON Schemas")
    pc.add_argument("--connect", default=DEFAULT_CONNECT, help=f"zenoh endpoint (default {DEFAULT_CONNECT})")
    pc.add_argument("--timeout", type=float, default=10.0, help="query timeout in seconds (default 10)")

    args = p.parse_args(argv)
    try:
        if args.command == "solve":
            if args.file == "-":
                payload = sys.stdin.buffer.read()
            else:
                with open(args.file, "rb") as f:
                    payload = f.read()
            with Client(args.connect, args.timeout) as c:
                out = c.solve(payload)
        elif args.command == "health":
            with Client(args.connect) as c:
                out = c.health(args.timeout)
        else:
            with Client(args.connect) as c:
                out = c.schema(args.timeout)
    except ContactError as e:
        _emit(e.reply)
        return 1
    except TransportError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    _emit(out)
    return 0


def _emit(value) -> None:
    """Print JSON to stdout; a closed pipe (e.g. `| head`) is not an error."""
    try:
        print(json.dumps(value, indent=2), flush=True)
    except BrokenPipeError:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())


if __name__ == "__main__":
    sys.exit(main())
