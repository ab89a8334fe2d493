"""The `contact` command line, run in this process by the built-in solver."""

from __future__ import annotations

import sys


def main() -> None:
    from contact_client._contact import cli

    sys.exit(cli(["contact", *sys.argv[1:]]))


if __name__ == "__main__":
    main()
