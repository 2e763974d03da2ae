"""The older spelling of the rendezvous campaign, kept as an alias of `ogk mc SCENARIO`:

    python -m ogk.missions.rendezvous.campaign SCENARIO --strategy snns --solver kernel --seeds 1-10 \
        [--unperturbed] [--third-bodies-in-model yes|no|scenario] [--workers 2] --json FILE

`--seeds A-B` (or 'A,B,C', or 'A') flies as many runs as seeds listed, with master seed A: run i
draws its noise from the engine's stream of (A, i) (ogk.sil.seeds), not from seed A + i as before
the campaign engine. Everything else is `ogk mc` (family.py): the envelope, the Parquet table, the
run log, --resume.
"""
from __future__ import annotations

import argparse
import sys

from ogk_host.scenario_file import read_header, resolve_scenario

from ogk.sil import command

from .family import FAMILY


def parse_seeds(text: str) -> list[int]:
    """'1-10' or '1,4,7' or '3'."""
    seeds: list[int] = []
    for part in text.split(","):
        if "-" in part:
            lo, hi = part.split("-", 1)
            seeds.extend(range(int(lo), int(hi) + 1))
        else:
            seeds.append(int(part))
    return seeds


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    pre = argparse.ArgumentParser(add_help=False)
    pre.add_argument("--seeds", default="1-10")
    known, rest = pre.parse_known_args(argv)
    seeds = parse_seeds(known.seeds)
    if not rest or rest[0].startswith("-"):
        print("usage: python -m ogk.missions.rendezvous.campaign SCENARIO [--seeds A-B] "
              "[ogk mc options]", file=sys.stderr)
        return 2
    header = read_header(resolve_scenario(rest[0]))
    args = command.parser_for(FAMILY, "python -m ogk.missions.rendezvous.campaign", header).parse_args(
        [*rest[1:], "--runs", str(len(seeds)), "--seed", str(seeds[0])])
    return command.fly(FAMILY, header, args)


if __name__ == "__main__":
    raise SystemExit(main())
