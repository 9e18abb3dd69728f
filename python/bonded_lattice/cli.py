"""Command-line tool ``bonded-lattice``."""

from __future__ import annotations

import argparse
import sys

from . import __version__
from .plugin import plugin_path


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bonded-lattice", description=__doc__)
    parser.add_argument("--version", action="version", version=f"bonded-lattice {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("info", help="print the package version and the plugin's location")
    args = parser.parse_args(argv)
    if args.command == "info":
        print(f"bonded-lattice {__version__}")
        print(f"plugin: {plugin_path()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
