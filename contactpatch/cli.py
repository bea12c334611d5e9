"""``contactpatch`` console script (the commands live in :mod:`contactpatch.study.cli`)."""

from __future__ import annotations

import sys

from .study.cli import build_parser, main

__all__ = ["build_parser", "main"]

if __name__ == "__main__":
    sys.exit(main())
