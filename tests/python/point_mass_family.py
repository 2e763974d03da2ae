"""The test family (issue 33): a point mass on a line brought to rest at the origin by a proportional
law, u = -k_r x - k_v v, from a dispersed start. It proves that a fifth family is one class
(FamilyDefaults gives what it does not have: tables, targets) and one registry line (`register`),
and it carries the engine's fault tests (test_campaign_faults.py): `--fault KIND:RUN` makes run RUN
raise a kernel error, kill its worker or hang; `--seconds-per-run` stretches a run. Not shipped."""
from __future__ import annotations

import argparse
import contextlib
import os
import signal
import sys
import time
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

import numpy as np
from ogk_bindings.kernel import KernelError
from ogk_host import scenario_file as sf

from ogk.missions import registry
from ogk.sil.engine import Flown
from ogk.sil.family import CampaignPlan, FamilyDefaults, Record, per_run
from ogk.sil.seeds import run_generator

MISSION = "point-mass"
SCENARIO = """schema = "ogk.point-mass/1"
mission = "point-mass"
name = "{name}"
source = "tests/python/point_mass_family.py"
[guidance]
law = "proportional"
position_gain_s2 = 1.0
velocity_gain_s = 1.4
[dispersions]
position_m = 10.0
velocity_m_s = 1.0
[acceptance]
position_error_m = {tolerance}
"""


#: `ogk` in a subprocess that knows the test family
OGK = [sys.executable, "-c", f"import sys; sys.path.insert(0, {str(Path(__file__).parent)!r}); "
       "import point_mass_family; point_mass_family.register(); from ogk.cli import main; "
       "sys.exit(main())"]


def write_scenario(path: Path, name: str = "point_mass", tolerance: float = 0.05) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(SCENARIO.format(name=name, tolerance=tolerance))
    return path


def register() -> None:
    """The family's one registry line (and its mission, accepted by the scenario header)."""
    registry.PACKAGES[MISSION] = __name__
    if MISSION not in sf.MISSIONS:
        sf.MISSIONS = (*sf.MISSIONS, MISSION)


@contextlib.contextmanager
def registered() -> Iterator[None]:
    """The family registered within, the shipped families only after."""
    packages, missions = dict(registry.PACKAGES), sf.MISSIONS
    register()
    try:
        yield
    finally:
        registry.PACKAGES.clear()
        registry.PACKAGES.update(packages)
        sf.MISSIONS = missions


def fly_point_mass(law: Mapping[str, float], x0: float, v0: float, duration_s: float = 10.0,
                   step_s: float = 0.01) -> tuple[float, float]:
    """The final position and velocity: x'' = -k_r x - k_v v, semi-implicit Euler."""
    x, v = x0, v0
    for _ in range(int(round(duration_s / step_s))):
        v += step_s * (-law["position_gain_s2"] * x - law["velocity_gain_s"] * v)
        x += step_s * v
    return x, v


def _fault(kind: str, run_id: int, at: int) -> None:
    if run_id != at:
        return
    if kind == "raise":
        raise KernelError(3, "ogk_point_mass_step")
    if kind == "kill":
        os.kill(os.getpid(), signal.SIGKILL)
    if kind == "hang":
        time.sleep(3600)


class PointMassFamily(FamilyDefaults):
    name = MISSION
    laws = ("proportional",)
    campaign_doc = "a dispersed start brought to rest by the proportional law"

    def load(self, header: sf.ScenarioHeader) -> dict[str, Any]:
        raw = sf.read_toml(header.path)
        sf.check_header(raw, header.path)
        top = sf.Section(raw, header.path, "")
        for key in ("schema", "mission", "name", "source"):
            top.text(key)
        g, d, a = top.section("guidance"), top.section("dispersions"), top.section("acceptance")
        out = {"law": {"position_gain_s2": g.number("position_gain_s2", positive=True),
                       "velocity_gain_s": g.number("velocity_gain_s", positive=True)},
               "sigma": (d.number("position_m", nonnegative=True),
                         d.number("velocity_m_s", nonnegative=True)),
               "tolerance_m": a.number("position_error_m", positive=True)}
        g.text("law")
        for section in (g, d, a, top):
            section.finish()
        return out

    def add_campaign_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--fault", default=None, metavar="KIND:RUN", help="raise, kill or hang")
        parser.add_argument("--seconds-per-run", type=float, default=0.0)

    def plan(self, header: sf.ScenarioHeader, options: Mapping[str, Any]) -> CampaignPlan:
        scn = self.load(header)
        fault = str(options.get("fault") or "none:-1").split(":")
        pause = float(options.get("seconds_per_run") or 0.0)

        def fly_one(run_id: int, run_seed: int) -> Record:
            _fault(fault[0], run_id, int(fault[1]))
            time.sleep(pause)
            x0, v0 = np.array(scn["sigma"]) * run_generator(run_seed).standard_normal(2)
            x_f, v_f = fly_point_mass(scn["law"], float(x0), float(v0))
            return {"x0_m": float(x0), "v0_m_s": float(v0), "x_f_m": x_f, "v_f_m_s": v_f}

        tol = scn["tolerance_m"]
        return CampaignPlan(
            family=self.name, law=header.law, mission=header.name, scenario_path=header.path,
            scenario_sha256=header.sha256, options=dict(options), products={},
            fly=per_run(fly_one), quantities=("x_f_m", "v_f_m_s"), acceptance={"x_f_m": tol},
            judge=lambda r: "" if abs(r["x_f_m"]) <= tol else f"tolerance: |x_f| > {tol:g}")

    def report(self, flown: Flown) -> tuple[str, dict[str, Any]]:
        worst = max(abs(r["x_f_m"]) for r in flown.records)
        return f"{flown.plan.mission}: {len(flown.records)} runs, worst |x_f| {worst:.3g} m", {}

    def add_run_arguments(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--x0", type=float, default=1.0, help="start [m]")

    def run(self, header: sf.ScenarioHeader, args: argparse.Namespace) -> int:
        """One flight from --x0 at rest."""
        x_f, v_f = fly_point_mass(self.load(header)["law"], args.x0, 0.0)
        print(f"x_f = {x_f:.6g} m, v_f = {v_f:.6g} m/s")
        return 0


FAMILY = PointMassFamily()
