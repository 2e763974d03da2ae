"""`ogk soak` / `make soak`: long campaigns of every family through the one engine, judged against the
envelope each law states (soak.toml at the repository root; docs/guides/campaigns.md, "make soak").

The plan names campaigns (scenario, runs, seed, the family's options) and, per campaign, the classes of
lost flights its law's documented envelope states with the largest fraction of the runs each may take.
A campaign's verdict comes from its envelope (ogk.campaign/1, `robustness`): every lost flight of a class
not stated, or more of a stated class than its fraction, is a violation. This module reads plans and
envelopes and writes the per-family summary; flying is `ogk mc` (the CLI runs it, one process each).
"""
from __future__ import annotations

import dataclasses
import math
import tomllib
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from ogk_bindings.errors import OgkInputError
from ogk_host.paths import WORK_ROOT, need_repository

from .robustness import short

#: the repository's plan (the shipped scenarios' soak campaigns)
DEFAULT_PLAN = WORK_ROOT / "soak.toml"


def default_plan() -> Path:
    """DEFAULT_PLAN; from an installed wheel, one OgkInputError line: the plan is the repository's."""
    need_repository("the default soak plan (soak.toml; or give PLAN)")
    return DEFAULT_PLAN


@dataclasses.dataclass(frozen=True)
class Stated:
    """A class of lost flights the law's envelope states, at most `max_fraction` of the runs."""

    cls: str
    max_fraction: float


@dataclasses.dataclass(frozen=True)
class SoakCampaign:
    name: str
    scenario: str
    runs: int
    seed: int
    options: tuple[str, ...] = ()
    stated: tuple[Stated, ...] = ()


def load_plan(path: str | Path = DEFAULT_PLAN) -> list[SoakCampaign]:
    """The campaigns of a soak plan; every bad key: one OgkInputError line naming it."""
    p = Path(path)
    try:
        raw = tomllib.loads(p.read_text(encoding="utf-8"))
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise OgkInputError(f"not a soak plan ({exc})", path=p) from None
    entries = raw.get("campaign")
    if not isinstance(entries, list) or not entries or set(raw) != {"campaign"}:
        raise OgkInputError("must hold [[campaign]] tables and nothing else", path=p, key="campaign")
    out: list[SoakCampaign] = []
    for i, e in enumerate(entries):
        key = f"campaign[{i}]"
        if not isinstance(e, dict):
            raise OgkInputError("must be a table", path=p, key=key)
        unknown = set(e) - {"name", "scenario", "runs", "seed", "options", "stated"}
        if unknown:
            raise OgkInputError(f"unknown key {sorted(unknown)[0]!r}", path=p, key=key)
        for k, kind in (("name", str), ("scenario", str), ("runs", int), ("seed", int)):
            if not isinstance(e.get(k), kind) or isinstance(e.get(k), bool):
                raise OgkInputError(f"must be a {kind.__name__}", path=p, key=f"{key}.{k}")
        if e["runs"] < 1 or e["seed"] < 0:
            raise OgkInputError("runs must be >= 1 and seed >= 0", path=p, key=key)
        options = e.get("options", [])
        if not isinstance(options, list) or not all(isinstance(o, str) for o in options):
            raise OgkInputError("must be a list of strings", path=p, key=f"{key}.options")
        stated = []
        for j, s in enumerate(e.get("stated", [])):
            sk = f"{key}.stated[{j}]"
            if (not isinstance(s, dict) or set(s) != {"class", "max_fraction"}
                    or not isinstance(s["class"], str)
                    or not isinstance(s["max_fraction"], (int, float))
                    or not 0.0 < float(s["max_fraction"]) <= 1.0):
                raise OgkInputError("must be {class = \"...\", max_fraction = (0, 1]}", path=p, key=sk)
            stated.append(Stated(s["class"], float(s["max_fraction"])))
        out.append(SoakCampaign(e["name"], e["scenario"], e["runs"], e["seed"], tuple(options),
                                tuple(stated)))
    names = [c.name for c in out]
    if len(set(names)) != len(names):
        raise OgkInputError("campaign names must differ (they name the outputs)", path=p, key="campaign")
    return out


def violations(doc: Mapping[str, Any], stated: Sequence[Stated]) -> list[str]:
    """Each class of lost flights of a campaign envelope that its stated envelope does not allow."""
    rob = doc["robustness"]
    allowed = {s.cls: s.max_fraction for s in stated}
    out = []
    for cls, e in rob["lost_by_class"].items():
        if cls not in allowed:
            out.append(f"{e['count']} x {cls}: not stated (runs "
                       f"{', '.join(str(i) for i in e['runs'][:8])}{', ...' if e['count'] > 8 else ''})")
        elif e["count"] > math.floor(allowed[cls] * rob["runs"] + 1e-9):
            out.append(f"{e['count']} x {cls}: more than the stated {allowed[cls]:g} of "
                       f"{rob['runs']} runs")
    return out


def family_summary(done: Sequence[tuple[SoakCampaign, Mapping[str, Any] | None, str, float]]) -> str:
    """Per family: its campaigns, runs, lost flights by class (stated or not), failed solves per
    flight, the worst run; `done`: (campaign, envelope or None when it aborted, note, wall s)."""
    families: dict[str, list[tuple[SoakCampaign, Mapping[str, Any] | None, str, float]]] = {}
    for c, doc, note, wall in done:
        families.setdefault(doc["family"] if doc else "(aborted)", []).append((c, doc, note, wall))
    lines = ["soak summary, per family (lost flights: stated = in the law's envelope, soak.toml)"]
    for fam, items in families.items():
        runs = sum(d["runs"] for _, d, _, _ in items if d)
        lost = sum(d["robustness"]["lost_flights"] for _, d, _, _ in items if d)
        lines.append(f"{fam}: {len(items)} campaigns, {runs} runs, {lost} lost")
        for c, doc, note, wall in items:
            if doc is None:
                lines.append(f"  {c.name}: ABORTED ({note})")
                continue
            rob = doc["robustness"]
            allowed = {s.cls for s in c.stated}
            lines.append(f"  {c.name} (seed {c.seed}, {rob['runs']} runs, {wall:.0f} s wall): "
                         f"{rob['lost_flights']} lost")
            for cls, e in rob["lost_by_class"].items():
                lines.append(f"    {e['count']} x {cls} [{'stated' if cls in allowed else 'NOT STATED'}]"
                             f" runs {', '.join(str(i) for i in e['runs'][:8])}"
                             f"{', ...' if e['count'] > 8 else ''}")
            s = rob.get("failed_solves")
            lines.append("    failed solves: -" if s is None else
                         f"    failed solves: {s['total']} ({s['runs_with_any']} runs), at most "
                         f"{s['per_run_max']} per flight"
                         + (f" (run {s['run_of_max']})" if s["run_of_max"] is not None else ""))
            w = rob.get("worst_run")
            if w is not None:
                lines.append(f"    worst run: {w['run_id']}, {w['quantity']} = {w['value']:.6g} "
                             f"(median {w['median']:.6g}; {short(w['from_median_robust_std'])} robust std, "
                             f"{short(w['from_median_std'])} std)")
            if note:
                lines.append(f"    {note}")
    return "\n".join(lines)
