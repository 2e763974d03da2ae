"""`ogk version`: harness and kernel versions."""
from __future__ import annotations

import argparse
from typing import Any


def run(args: argparse.Namespace) -> int:
    import ogk
    from ogk_bindings import kernel

    print(f"ogk harness {ogk.__version__}")
    print(f"ogk kernel  {kernel.version()}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser("version", help="print the harness and kernel versions")
    p.set_defaults(func=run)
