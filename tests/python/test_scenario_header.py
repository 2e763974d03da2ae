"""One scenario header for every mission family (docs/guides/adding-a-mission.md, "The scenario header"):
`schema = "ogk.<mission>/N"` checked against `mission`, `[guidance] law`, `[dispersions]`,
`[acceptance]` (a stated default when absent) and the optional `[paper_results]`.

Checked here: every shipped scenario carries the header and its typed object the common attribute
names; each old spelling of a family's dialect is refused through `ogk` with one line naming the
file, the key and what to rename it to (exit 2, before any computation); a scenario without
[acceptance] gets its family's stated default; a scenario without paper results loads and flies
(`ogk mc`), with no paper column and no NaN in its JSON."""
from __future__ import annotations

import dataclasses
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from ogk_bindings.errors import OgkInputError
from ogk_host.binary import scenario as binary
from ogk_host.low_thrust_transfer import scenario as transfer
from ogk_host.orbit_injection import scenario as injection
from ogk_host.proximity import scenario as proximity
from ogk_host.rendezvous import scenario as rendezvous
from ogk_host.scenario_file import MISSIONS, read_header, read_toml, schema_of

from ogk.missions import registry

REPO = Path(__file__).resolve().parents[2]
SCENARIOS = REPO / "scenarios"
OGK = Path(sys.executable).parent / "ogk"
LOADERS = {injection.MISSION: injection, transfer.MISSION: transfer, rendezvous.MISSION: rendezvous,
           binary.MISSION: binary, proximity.MISSION: proximity}
SHIPPED = sorted(SCENARIOS.glob("*.toml"))


def ogk(*args: str, timeout: float = 120.0) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(OGK), *args], capture_output=True, text=True, timeout=timeout, cwd=REPO)


def read_toml_text(text: str) -> dict:
    import tomllib
    return tomllib.loads(text)


def edited(tmp_path: Path, name: str, old: str, new: str) -> Path:
    """A copy of scenarios/NAME.toml with the first match of the regular expression `old` replaced."""
    text = (SCENARIOS / f"{name}.toml").read_text()
    assert re.search(old, text, flags=re.M), old
    path = tmp_path / f"{name}_edited.toml"
    path.write_text(re.sub(old, new, text, count=1, flags=re.M))
    return path


# ------------------------------------------------------------------------------------ the header

@pytest.mark.req("OGK-HAR-006")
def test_the_families_are_the_registry_s() -> None:
    assert set(MISSIONS) == set(registry.PACKAGES) == set(LOADERS)
    for mission, module in LOADERS.items():
        assert module.SCHEMA == schema_of(mission) == f"ogk.{mission}/1"


@pytest.mark.req("OGK-HAR-006")
@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_every_shipped_scenario_carries_the_header(path: Path) -> None:
    raw = read_toml(path)
    header = read_header(path)
    assert raw["schema"] == header.schema == f"ogk.{raw['mission']}/1"
    assert header.mission == raw["mission"] and header.law == raw["guidance"]["law"]
    assert "reference" not in raw                       # the paper's figures: [paper_results] only
    scenario = LOADERS[header.mission].load_scenario(path)
    # the same attribute names in every family
    assert dataclasses.is_dataclass(scenario.acceptance)
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(scenario.acceptance, dataclasses.fields(scenario.acceptance)[0].name, 0.0)
    assert scenario.paper_results is None or isinstance(scenario.paper_results, dict)
    assert (scenario.paper_results is None) == ("paper_results" not in raw)
    assert dataclasses.is_dataclass(scenario.dispersions)
    assert "dispersions" in raw


# ------------------------------------------------------------------------------------ old spellings

#: (scenario, regex, replacement, key named, the new spelling named)
OLD = [
    ("leo_geo", r'^schema = .*$', 'schema = "ogk.leo_geo/1"', "schema", '"ogk.orbit-injection/1"'),
    ("scout_upper_stage", r'^schema = .*$', 'schema = "ogk.leo_geo/1"', "schema",
     '"ogk.orbit-injection/1"'),
    ("rendezvous_nep_min_time", r'^schema = .*$', 'schema = "ogk.rendezvous/1"', "schema",
     '"ogk.low-thrust-rendezvous/1"'),
    ("moshup", r'^schema = .*$', 'schema = "ogk.binary/1"', "schema", '"ogk.binary-asteroid/1"'),
    ("apophis_cubesat", r'^schema = .*\n', "", "schema", '"ogk.low-thrust-transfer/1"'),
    ("leo_geo", r'^mission = .*$', 'mission = "binary-asteroid"', "schema", '"ogk.binary-asteroid/1"'),
    # MPSP: [reference.*] and [perturbations.*]
    ("apophis_cubesat", r"^\[paper_results\.table3\]", "[reference.table3]", "reference.table3",
     "[paper_results.table3]"),
    ("apophis_cubesat", r"^\[paper_results\.nominal\]", "[reference.nominal]", "reference.nominal",
     "[paper_results.nominal]"),
    ("apophis_cubesat", r"^\[dispersions\.terminal\]", "[perturbations.terminal]",
     "perturbations.terminal", "[dispersions.terminal]"),
    # rendezvous: the thrust-angle noise back in [perturbations] (its forces stay there)
    ("rendezvous_nep_min_fuel", r"^\[dispersions\].*\n", "", "perturbations.thrust_angle_sigma_rad",
     "[dispersions] thrust_angle_sigma_rad"),
    # rendezvous: the target's keys named after Mars (any target now: [target] name)
    ("rendezvous_nep_min_time", r"^target_orbit_radius_m", "mars_orbit_radius_m",
     "problem.mars_orbit_radius_m", "[problem] target_orbit_radius_m"),
    ("rendezvous_sep_min_fuel", r"^target_soi_radius_m", "mars_soi_radius_m",
     "convergence.mars_soi_radius_m", "[convergence] target_soi_radius_m"),
    # binary: per-transfer paper_* keys, paper_converged_percent, the draws in [monte_carlo]
    ("moshup", r"^(\[transfers\.l2_to_l1_halo\].*\n)", r"\1paper_fuel_g = 13.64\n",
     "transfers.l2_to_l1_halo.paper_fuel_g", "[paper_results.transfers.l2_to_l1_halo] fuel_g"),
    ("moshup", r"^max_iter = 40\n", "max_iter = 40\npaper_converged_percent = [99.15]\n",
     "monte_carlo.paper_converged_percent", "[paper_results.table3] converged_percent"),
    ("moshup", r"^\[dispersions\]\n", "", "monte_carlo.levels_percent", "[dispersions] levels_percent"),
]


@pytest.mark.req("OGK-HAR-006")
@pytest.mark.parametrize("name, old, new, key, spelling", OLD,
                         ids=[f"{o[0]}:{o[3]}" for o in OLD])
def test_old_spelling_is_one_line_with_the_new_name(tmp_path: Path, name: str, old: str, new: str,
                                                    key: str, spelling: str) -> None:
    path = edited(tmp_path, name, old, new)
    out = tmp_path / "mc.json"
    for args in (("tables", str(path)), ("mc", str(path), "--runs", "1", "--json", str(out))):
        res = ogk(*args)
        assert res.returncode == 2, res.stdout + res.stderr
        lines = res.stderr.strip().splitlines()
        assert len(lines) == 1 and "Traceback" not in res.stderr, res.stderr
        assert f"{path}: {key}: " in lines[0] and spelling in lines[0], lines[0]
        assert "rename" in lines[0] or "missing key" in lines[0], lines[0]
        assert not out.exists()
    # the family's loader says the same to a Python caller
    mission = read_toml(SCENARIOS / f"{name}.toml")["mission"]
    if "mission" not in old:
        with pytest.raises(OgkInputError) as err:
            LOADERS[mission].load_scenario(path)
        assert err.value.key == key and spelling in str(err.value)


# ------------------------------------------------------------------------------------ acceptance

@pytest.mark.req("OGK-HAR-006")
def test_orbit_injection_default_acceptance(tmp_path: Path) -> None:
    path = edited(tmp_path, "leo_geo", r"^\[acceptance\]\n(?:(?!\[).*\n)*", "")
    scn = injection.load_scenario(path)
    assert "acceptance" not in read_toml(path)
    assert scn.acceptance == injection.Acceptance(1000.0, 1000.0 / scn.target_radius_m, 10.0)
    assert injection.load_scenario(SCENARIOS / "leo_geo.toml").acceptance.velocity_error_m_s == 20.0


@pytest.mark.req("OGK-HAR-006")
def test_low_thrust_transfer_default_acceptance_is_the_mpsp_tolerance(tmp_path: Path) -> None:
    scn = transfer.load_scenario(SCENARIOS / "apophis_cubesat.toml")
    assert "acceptance" not in read_toml(scn.path)
    assert scn.acceptance == transfer.Acceptance(scn.mpsp.tol_position_km, scn.mpsp.tol_velocity_km_s)
    assert scn.acceptance == transfer.Acceptance(500.0, 0.1)
    path = edited(tmp_path, "apophis_cubesat", r"^\[dispersions\.initial\]",
                  "[acceptance]\nposition_error_km = 50.0\n\n[dispersions.initial]")
    assert transfer.load_scenario(path).acceptance == transfer.Acceptance(50.0, 0.1)
    bad = edited(tmp_path, "apophis_cubesat", r"^\[dispersions\.initial\]",
                 "[acceptance]\nposition_error_m = 50.0\n\n[dispersions.initial]")
    with pytest.raises(OgkInputError) as err:
        transfer.load_scenario(bad)
    assert err.value.key == "acceptance.position_error_m" and "unknown key" in str(err.value)


@pytest.mark.req("OGK-HAR-006")
def test_rendezvous_default_acceptance_is_the_arrival_condition(tmp_path: Path) -> None:
    from ogk.missions.rendezvous.family import judge
    scn = rendezvous.load_scenario(SCENARIOS / "rendezvous_nep_min_time.toml")
    conv = scn.convergence
    # the propellant limit defaults to what the vehicle carries: m0 - [spacecraft] dry_mass_kg
    assert scn.acceptance == rendezvous.Acceptance(conv.target_soi_radius_m, conv.velocity_error_m_s,
                                                   scn.initial_mass_kg - scn.dry_mass_kg)
    arrived = {"converged": True, "reason": "converged", "final_position_miss_km": 5.0e5,
               "final_velocity_miss_m_s": 900.0, "fuel_kg": 600.0}
    assert judge(scn.acceptance, arrived) == ""
    assert judge(scn.acceptance, {**arrived, "converged": False, "reason": "max_replans"}) \
        == "not arrived: max_replans"
    path = edited(tmp_path, "rendezvous_nep_min_time", r"^\[paper_results\]",
                  "[acceptance]\npropellant_kg = 550.0\n\n[paper_results]")
    limited = rendezvous.load_scenario(path).acceptance
    assert limited == rendezvous.Acceptance(conv.target_soi_radius_m, conv.velocity_error_m_s, 550.0)
    assert judge(limited, arrived).startswith("propellant: 600 kg > 550")


@pytest.mark.req("OGK-HAR-006")
def test_binary_default_acceptance_is_the_corrector_tolerance(tmp_path: Path) -> None:
    from ogk_host.binary import transfers as T
    scn = binary.load_scenario(SCENARIOS / "moshup.toml")
    assert scn.acceptance == binary.Acceptance(None)
    assert scn.acceptance.tolerance(T.monte_carlo_spec(scn).tol) == 5.0e-5        # ogk mc
    assert scn.acceptance.tolerance(T.solver_settings(scn).tol) == 1.0e-6         # ogk blt / run
    path = edited(tmp_path, "moshup", r"^\[dispersions\]",
                  "[acceptance]\nerror_tolerance = 1.0e-5\n\n[dispersions]")
    assert binary.load_scenario(path).acceptance.tolerance(5.0e-5) == 1.0e-5


# ------------------------------------------------------------------------------------ paper results

@pytest.mark.req("OGK-HAR-006")
@pytest.mark.parametrize("name", ["leo_geo", "apophis_cubesat", "rendezvous_nep_min_time", "moshup"])
def test_every_family_loads_without_paper_results(tmp_path: Path, name: str) -> None:
    text = (SCENARIOS / f"{name}.toml").read_text()
    bare = re.sub(r"^\[paper_results(\.[^\]]*)?\][^\n]*\n(?:(?!\[).*\n?)*", "", text, flags=re.M)
    assert "paper_results" not in read_toml_text(bare)
    path = tmp_path / f"{name}.toml"
    path.write_text(bare)
    mission = read_toml(path)["mission"]
    scn = LOADERS[mission].load_scenario(path)
    assert scn.paper_results is None


@pytest.mark.req("OGK-HAR-006", "OGK-HAR-002")
def test_binary_report_prints_the_paper_column_only_with_paper_figures() -> None:
    from ogk.missions.binary.one_transfer import report_lines
    doc = {"scenario": "s", "transfer": "t", "kind": "single-burn", "thrust_n": 0.024, "corrector": "nrpc",
           "jacobian": "variational", "converged": True, "status": "OGK_OK", "iterations": 5,
           "final_error": 1e-7, "final_error_dop853": 1e-7, "burn_time_s": 600.0, "flight_time_s": 600.0,
           "fuel_g": 1.0, "delta_v_m_s": 0.1, "closest_approach_m": [900.0, 300.0],
           "kernel_solve_wall_s": 0.01}
    assert "paper" not in "\n".join(report_lines({**doc, "paper": {}}))
    with_paper = report_lines({**doc, "paper": {"fuel_g": 13.64}})
    assert "paper" in with_paper[1] and "13.64" in "\n".join(with_paper)


@pytest.mark.req("OGK-HAR-006", "OGK-HAR-002")
def test_mpsp_campaign_without_paper_results(tmp_path: Path) -> None:
    """`ogk mc` of the Apophis scenario with its paper tables removed: the paper's cases fly, the
    report has no paper column and the JSON no NaN (null where a number is missing)."""
    text = (SCENARIOS / "apophis_cubesat.toml").read_text()
    bare = re.sub(r"^\[paper_results(\.[^\]]*)?\][^\n]*\n(?:(?!\[).*\n?)*", "", text, flags=re.M)
    path = tmp_path / "apophis_bare.toml"
    path.write_text(bare)
    out = tmp_path / "mc.json"
    res = ogk("mc", str(path), "--cases", "paper", "--runs", "2", "--seed", "3", "--json", str(out),
              timeout=600)
    assert res.returncode in (0, 1), res.stdout + res.stderr
    assert "Traceback" not in res.stderr
    assert "paper" not in res.stdout.split("\n", 1)[1].lower().replace("--cases paper", ""), res.stdout
    raw = out.read_text()
    assert "NaN" not in raw and "Infinity" not in raw
    doc = json.loads(raw)
    assert doc["runs"] == 2 and doc.get("paper") is None          # no paper: no "paper" key
    assert doc["acceptance"] == {"converged": True, "dr_f_km": 500.0, "dv_f_kmps": 0.1}
