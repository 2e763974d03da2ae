"""`ogk replay CAMPAIGN RUN_ID [--plots DIR] [--json FILE]`: one run of a campaign flown again from
the campaign's JSON envelope (scenario, options, seed, ground products checked by SHA-256), compared
bit for bit with its row of the Parquet table; with its time histories and plots where the family
draws them. Exit 0 when bit-exact, 1 when a value differs, 2 on bad input."""
from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any


def register(sub: Any) -> None:
    p = sub.add_parser("replay", help="fly one run of a campaign again, bit-exact",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("campaign", metavar="CAMPAIGN", help="the campaign's JSON (ogk mc --json)")
    p.add_argument("run_id", metavar="RUN_ID", type=int)
    p.add_argument("--plots", default=None, metavar="DIR", help="PNG plots of the run")
    p.add_argument("--json", default=None, metavar="FILE", help="the run's record as JSON")
    p.set_defaults(func=_replay)


def _replay(args: argparse.Namespace) -> int:
    _select_precision(args.campaign)
    from ogk.cli.campaign_flow import replay
    return replay(args.campaign, args.run_id, args.plots, args.json)


def _select_precision(campaign: str) -> None:
    """The kernel precision the campaign flew (its envelope's "precision"), selected before anything
    imports the bindings (ogk.sil.precision): a single campaign's run is replayed on the float kernel.
    An unreadable envelope is left to the replay's own check of it."""
    from ogk.sil import precision
    try:
        want = json.loads(Path(campaign).read_text(encoding="utf-8")).get("precision")
    except (OSError, ValueError, AttributeError):
        return
    if want in precision.CHOICES:
        precision.select(want)
