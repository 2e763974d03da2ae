"""`ogk report CAMPAIGN`: a campaign's tables from its JSON envelope and Parquet table, the paper's
columns beside ours when the scenario carries them; nothing is flown. Exit 1 when a run failed."""
from __future__ import annotations

import argparse
from typing import Any


def register(sub: Any) -> None:
    p = sub.add_parser("report", help="a campaign's tables from its JSON (nothing flown)",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("campaign", metavar="CAMPAIGN", help="the campaign's JSON (ogk mc --json)")
    p.set_defaults(func=lambda args: _report(args.campaign))


def _report(campaign: str) -> int:
    from ogk.cli.campaign_flow import report
    return report(campaign)
