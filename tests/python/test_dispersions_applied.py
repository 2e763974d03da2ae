"""Dispersions proven applied (issue 23 item 2; ogk.sil.dispersion_check, docs/guides/campaigns.md,
"Dispersions proven applied"): every family's shipped scenario, drawn through the family's own
plan, carries each declared dispersion with spread > 0 and the distribution its [dispersions]
states (the expectations read here from the TOML text itself, not from the family); the records of
flown runs carry the same values bit for bit; a dispersion the family draws but does not apply
(monkeypatched) and one applied with the wrong size fail the check; an edited mission no shipped
scenario names is checked against its own values; `ogk mc` prints the verdict, writes it into the
envelope and exits 1 when a dispersion is not applied.

Cost: draw-only campaigns (a few hundred to a thousand runs drawn, not flown) plus 2-6 flown runs
per family; the plans are built once per module (the binary nominal design is the longest)."""
from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from ogk_host.scenario_file import read_header, resolve_scenario

from ogk.missions import registry
from ogk.sil import dispersion_check as dc
from ogk.sil.engine import fly_campaign

from scenario_edit import set_key

ALARM_S = 240
pytestmark = pytest.mark.usefixtures("alarm")

REPO = Path(__file__).resolve().parents[2]

#: shipped scenario -> (family options of the check's campaigns, draw-only runs, flown runs)
SHIPPED = {
    "leo_geo": ({"guidance": "nominal"}, 1000, 2),
    "scout_upper_stage": ({"guidance": "nominal"}, 1000, 0),   # its nominal: 90 s, see _plan
    "apophis_cubesat": ({}, 900, 6),
    "rendezvous_nep_min_fuel": ({}, 1000, 0),
    "rendezvous_nep_min_time": ({}, 1000, 2),
    "rendezvous_sep_min_fuel": ({}, 1000, 0),
    "moshup": ({}, 600, 2),
    "proximity_approach": ({}, 1000, 0),
}
SEED = 20231

_PLANS: dict[tuple[str, str], object] = {}


def _plan(scenario: str | Path, options: dict | None = None, key: str | None = None):
    """The family's real campaign plan of a scenario (built once per module). Scout: the
    family's plan builder without the nominal (`flights.campaign_plan` with no reference): the
    draws do not depend on the nominal, which takes 90 s to solve."""
    options = dict(SHIPPED.get(str(scenario), ({}, 0, 0))[0] if options is None else options)
    k = (str(scenario), key or repr(sorted(options.items())))
    if k not in _PLANS:
        header = read_header(resolve_scenario(str(scenario)))
        fam = registry.family(header)
        if str(scenario) == "scout_upper_stage":
            from ogk.missions.orbit_injection.flights import campaign_plan
            from ogk.missions.orbit_injection.dispersions import DispersionSwitches
            from ogk.missions.orbit_injection.guidance import NominalOpenLoopGuidance
            from ogk.missions.orbit_injection.sil import SilSettings
            _PLANS[k] = campaign_plan(fam.load(header), None, DispersionSwitches(), SilSettings(),
                                      NominalOpenLoopGuidance, "nominal", None, header.path,
                                      header.law)
        else:
            _PLANS[k] = fam.plan(header, options)
    return _PLANS[k]


def _toml(scenario: str | Path) -> dict:
    with resolve_scenario(str(scenario)).open("rb") as f:
        return tomllib.load(f)


def _leaves(table: dict, prefix: str = "") -> dict[str, object]:
    out: dict[str, object] = {}
    for k, v in table.items():
        if isinstance(v, dict):
            out.update(_leaves(v, f"{prefix}{k}."))
        else:
            out[prefix + k] = v
    return out


def expected_from_toml(scenario: str | Path) -> dict[str, tuple[str, object]]:
    """What each family's documentation (docs/guides/adding-a-mission.md, the scenario comments) says a
    campaign draws, read from the TOML text alone: key -> (kind, parameters)."""
    doc = _toml(scenario)
    disp = _leaves(doc.get("dispersions", {}))
    mission = doc["mission"]
    out: dict[str, tuple[str, object]] = {}
    if mission == "orbit-injection":       # Tables 3-5, eq. (55): zero-mean Gaussian 1-sigma
        for k, v in disp.items():
            if k == "thrust.harmonics":
                continue
            size = 2 * int(disp["thrust.harmonics"]) if k == "thrust.coefficient_sigma" else None
            out[k] = ("gaussian", (float(v), size)) if float(v) > 0 else ("constant", (0.0, size))
    elif mission == "low-thrust-rendezvous":
        s = float(disp["thrust_angle_sigma_rad"])
        out["thrust_angle_sigma_rad"] = ("gaussian", (s, None)) if s > 0 else ("constant", (0.0, None))
    elif mission == "binary-asteroid":     # level i mod L; xi ~ N(0, sf^2) clipped to [-1, 1]
        out["levels_percent"] = ("cycle", tuple(float(v) for v in disp["levels_percent"]))
        out["sigma_fraction"] = ("clipped", float(disp["sigma_fraction"]))
    elif mission == "proximity-approach":   # Gaussian sigmas; the start's position, velocity: 2 each
        for k, v in disp.items():
            size = 2 if k in ("initial_position_sigma_m", "initial_velocity_sigma_m_s") else None
            out[k] = ("gaussian", (float(v), size)) if float(v) > 0 else ("constant", (0.0, size))
    elif mission == "low-thrust-transfer":  # uniform within each listed range, kind i mod 3
        k, e = disp["initial.kappa"], disp["thrust.eta_percent"]
        v = np.array(disp["terminal.delta_final_position_LU"], dtype=float)
        out["initial.kappa"] = ("uniform", (min(k), max(k), 0))
        out["terminal.delta_final_position_LU"] = ("uniform", (tuple(v.min(0)), tuple(v.max(0)), 1))
        out["thrust.eta_percent"] = ("uniform", (min(e), max(e), 2))
    return out


def _values(records, keys) -> np.ndarray:
    rows = [[r[k] for k in keys] for r in records if all(r.get(k) is not None for k in keys)]
    return np.array(rows, dtype=float)


@pytest.mark.req("OGK-HAR-016")
@pytest.mark.parametrize("scenario", SHIPPED)
def test_every_shipped_scenario_applies_its_declared_dispersions(scenario):
    """Draw-only campaign of the family's own plan: the check passes, every drawn key is tested
    (not merely present), and each key's values match the TOML's statement independently: the
    sample std against sigma (Gaussian: the chi-square 99.9 % interval), uniform ranges hit
    near both ends, cycles exact, clipped values inside [-1, 1]."""
    from scipy import stats
    plan = _plan(scenario)
    _, runs, _ = SHIPPED[scenario]
    recs = dc.draw_only(plan, runs, SEED)
    res = dc.check_plan(plan, recs)
    assert res is not None and res.ok, res.summary()
    by_key = {e.key: e for e in res.entries}
    assert set(by_key) == set(_leaves(_toml(scenario)["dispersions"]))
    for key, (kind, par) in expected_from_toml(scenario).items():
        entry = by_key[key]
        if kind == "gaussian":
            sigma, size = par
            keys = [f"disp.{key}"] if size is None else [f"disp.{key}[{i}]" for i in range(size)]
            x = _values(recs, keys).ravel()
            assert entry.status == "tested" and x.size == runs * len(keys)
            lo, hi = (math.sqrt(stats.chi2.ppf(q, x.size) / x.size) for q in (5e-4, 1 - 5e-4))
            assert lo < math.sqrt(np.mean(x ** 2)) / sigma < hi, key
        elif kind == "constant":
            _, size = par
            keys = [f"disp.{key}"] if size is None else [f"disp.{key}[{i}]" for i in range(size)]
            assert entry.status == "exact" and np.all(_values(recs, keys) == 0.0)
        elif kind == "cycle":
            got = [r[f"disp.{key}"] for r in recs]
            assert got == pytest.approx([par[i % len(par)] for i in range(runs)], rel=1e-12)
        elif kind == "clipped":
            x = _values(recs, [k for k in recs[0] if k.startswith(f"disp.{key}[")]).ravel()
            assert entry.status == "tested" and np.all(np.abs(x) <= 1.0 + 1e-12)
            inside = x[np.abs(x) < 1.0 - 1e-9]       # the clipped normal's std, by quadrature
            assert np.std(x) == pytest.approx(_clipped_std(par), rel=0.05)
            assert inside.size > 0.99 * x.size
        elif kind == "uniform":
            lo, hi, phase = par
            keys = [k for k in recs[0] if k == f"disp.{key}" or k.startswith(f"disp.{key}[")]
            x = _values([r for r in recs if r["run_id"] % 3 == phase], keys)
            assert entry.status == "tested" and x.shape[0] == runs // 3
            lo_, hi_ = np.broadcast_to(lo, x.shape[1:]), np.broadcast_to(hi, x.shape[1:])
            span = hi_ - lo_
            assert np.all(x >= lo_) and np.all(x <= hi_)
            # n uniform draws leave less than 2 % of the range empty at an end (P < 1e-3 each)
            assert np.all(x.min(0) - lo_ < 0.02 * span) and np.all(hi_ - x.max(0) < 0.02 * span)
            assert np.allclose(x.mean(0), (lo_ + hi_) / 2, atol=4 * span / math.sqrt(12 * len(x)))
            assert all(r[keys[0]] is None for r in recs if r["run_id"] % 3 != phase)


def _clipped_std(sigma: float) -> float:
    """Std of clip(N(0, sigma^2), -1, 1): E[x^2] = int_{-1}^{1} x^2 phi + P(|z| > 1/sigma)."""
    from scipy import integrate, stats
    inner = integrate.quad(lambda x: x * x * stats.norm.pdf(x, scale=sigma), -1.0, 1.0)[0]
    return math.sqrt(inner + 2.0 * stats.norm.sf(1.0 / sigma))


@pytest.mark.req("OGK-HAR-016")
@pytest.mark.parametrize("scenario", [s for s, (_, _, n) in SHIPPED.items() if n])
def test_flown_records_carry_the_drawn_values_bit_for_bit(scenario):
    """A few runs flown by the family's chunk flight carry exactly the disp.* values the
    draw-only path gives for the same seeds (so the distribution test above is about the flown
    values), and the check passes on them."""
    plan = _plan(scenario)
    n = SHIPPED[scenario][2]
    flown = fly_campaign(plan, n, SEED, progress=False)
    drawn = dc.draw_only(plan, n, SEED)
    for f, d in zip(flown.records, drawn):
        disp = {k: v for k, v in f.items() if k.startswith(dc.PREFIX)}
        assert disp and disp == {k: v for k, v in d.items() if k.startswith(dc.PREFIX)}
    res = dc.check_plan(plan, flown.records)
    assert res is not None and not res.structural_errors, res.summary()


def _forget(monkeypatch, scenario: str) -> str:
    """Monkeypatches the family so that it draws a dispersion and does not apply it; returns the
    dispersion's key."""
    if scenario == "leo_geo":
        from ogk.missions.orbit_injection import flights
        real = flights.draw_runs

        def draw_runs(*a, **k):
            draws, gens = real(*a, **k)
            d_state = draws.d_state.copy()
            d_state[:, 0] = 0.0                      # the radius sigma forgotten
            return dataclasses.replace(draws, d_state=d_state), gens
        monkeypatch.setattr(flights, "draw_runs", draw_runs)
        return "initial_state.radius_m"
    if scenario == "rendezvous_nep_min_time":
        from ogk.missions.rendezvous import closed_loop, dispersions
        for module in (closed_loop, dispersions):      # the family's one switch of the noise
            monkeypatch.setattr(module, "sigma_flown", lambda scenario, perturbed: 0.0)
        return "thrust_angle_sigma_rad"
    if scenario == "apophis_cubesat":
        from ogk.missions.low_thrust_transfer import family
        real_t = family.thrust_case
        monkeypatch.setattr(family, "thrust_case", lambda setup, eta: dataclasses.replace(
            real_t(setup, eta), thrust_scale=1.0))   # eta drawn, T_max left nominal
        return "thrust.eta_percent"
    from ogk.missions.binary import convergence_run as bc
    real_p = bc.perturbed

    def perturbed(nominal, level, sigma_fraction, rng):
        guess, d = real_p(nominal, level, sigma_fraction, rng)
        guess.segments[:, 6] = nominal.transfer.segments[:, 6]   # durations not perturbed
        return guess, d
    monkeypatch.setattr(bc, "perturbed", perturbed)
    return "sigma_fraction"


@pytest.mark.req("OGK-HAR-016")
@pytest.mark.parametrize("scenario", [s for s, (_, _, n) in SHIPPED.items() if n])
def test_a_dispersion_drawn_and_not_applied_fails_the_check(scenario, monkeypatch):
    """The family draws the value and forgets to apply it (AVSLab/basilisk issue 1164): the check
    names the key, zero spread, as a structural error (not a distribution warning), on draw-only
    records and on flown ones."""
    plan = _plan(scenario)
    key = _forget(monkeypatch, scenario)
    flown = 6 if scenario == "apophis_cubesat" else 2     # >= 2 runs of the thrust kind
    for recs in (dc.draw_only(plan, 60, SEED), fly_campaign(plan, flown, SEED, progress=False).records):
        res = dc.check_plan(plan, recs)
        assert res is not None and not res.ok
        bad = [m for m in res.structural_errors if m.startswith(key + ":")]
        assert bad and "zero spread" in bad[0], res.summary()
        assert all(m.startswith(key + ":") for m in res.structural_errors)


@pytest.mark.req("OGK-HAR-016")
def test_a_dispersion_applied_in_the_wrong_unit_fails_the_distribution_test(monkeypatch):
    """The declination sigma applied in degrees instead of radians (x 57.3): spread > 0, so only
    the distribution tests can see it, and they do."""
    from ogk.missions.orbit_injection import flights
    plan = _plan("leo_geo")
    real = flights.draw_runs

    def draw_runs(*a, **k):
        draws, gens = real(*a, **k)
        d_state = draws.d_state.copy()
        d_state[:, 2] *= 180.0 / math.pi
        return dataclasses.replace(draws, d_state=d_state), gens
    monkeypatch.setattr(flights, "draw_runs", draw_runs)
    res = dc.check_plan(plan, dc.draw_only(plan, 200, SEED))
    assert not res.structural_errors
    assert {m.split(":")[0] for m in res.statistical_failures} == {"initial_state.declination_rad"}
    tests = " ".join(res.statistical_failures)
    assert "Kolmogorov-Smirnov" in tests and "variance" in tests


@pytest.mark.req("OGK-HAR-016", "OGK-HAR-007")
def test_an_edited_mission_is_checked_against_its_own_dispersions(tmp_path):
    """A GEO mission no shipped scenario names (leo_geo.toml edited as a user would: radius sigma
    1 km, attitude yaw not dispersed, thrust coefficients 0.05): its campaign passes against its
    own [dispersions], and its records fail against the shipped scenario's statement (the check
    sees the values, not only their presence)."""
    text = (REPO / "scenarios" / "leo_geo.toml").read_text()
    text = set_key(text, "dispersions.initial_state", "radius_m", "1.0e3")
    text = set_key(text, "dispersions.attitude", "yaw_rad", "0.0")
    text = set_key(text, "dispersions.thrust", "coefficient_sigma", "0.05")
    text = text.replace('name = "leo_geo"', 'name = "geo_edited"', 1)
    path = tmp_path / "geo_edited.toml"
    path.write_text(text)
    plan = _plan(path, {"guidance": "nominal"})
    recs = dc.draw_only(plan, 800, SEED)
    res = dc.check_plan(plan, recs)
    assert res.ok, res.summary()
    status = {e.key: e.status for e in res.entries}
    assert status["attitude.yaw_rad"] == "exact" and status["initial_state.radius_m"] == "tested"
    x = _values(recs, ["disp.initial_state.radius_m"]).ravel()
    assert 950.0 < np.std(x) < 1050.0
    shipped = dc.check_plan(_plan("leo_geo"), recs)
    failed = {m.split(":")[0] for m in shipped.structural_errors + shipped.statistical_failures}
    assert failed == {"initial_state.radius_m", "attitude.yaw_rad", "thrust.coefficient_sigma"}


@pytest.mark.req("OGK-HAR-016")
def test_the_paper_cases_are_checked_exactly_as_listed():
    """Apophis --cases paper: nothing drawn; each of the 23 cases is applied as its table lists
    it (kappa, the cube's vertices, eta), checked exactly, and a case flown with another value
    fails."""
    plan = _plan("apophis_cubesat", {"cases": "paper"})
    recs = dc.draw_only(plan, 23, SEED)
    res = dc.check_plan(plan, recs)
    assert res.ok and all(e.status in ("exact", "parameter") for e in res.entries), res.summary()
    disp = _toml("apophis_cubesat")["dispersions"]
    assert [r["disp.initial.kappa"] for r in recs[:9]] == pytest.approx(disp["initial"]["kappa"])
    assert [r["disp.thrust.eta_percent"] for r in recs[17:]] == pytest.approx(
        disp["thrust"]["eta_percent"])
    recs[3]["disp.initial.kappa"] += 0.01
    assert any(m.startswith("initial.kappa: 1 values not as stated")
               for m in dc.check_plan(plan, recs).structural_errors)


# ---------------------------------------------------------------- the check itself, synthetic records

def _records(n: int, **columns) -> list[dict]:
    return [{"run_id": i, "failure": "", **{k: v[i] for k, v in columns.items()}} for i in range(n)]


@pytest.mark.req("OGK-HAR-016")
def test_the_check_refuses_what_is_not_applied_as_declared():
    """Each structural error on synthetic records: missing key, undeclared disp.* key, a scenario
    key no declaration names, zero spread, a value outside a uniform range, a value on a run the
    dispersion does not apply to, a missing value on a run that did not fail (allowed on a failed
    one), constant and cycle values not as stated."""
    rng = np.random.default_rng(1)
    g = dc.Declared("a", dc.Gaussian(2.0))
    ok = _records(50, **{"disp.a": rng.normal(0, 2.0, 50)})
    assert dc.check([g], ok, {"a": 2.0}).ok
    assert "missing from the records" in dc.check([g], _records(5), {"a": 2.0}).structural_errors[0]
    extra = [{**r, "disp.b": 0.0} for r in ok]
    assert "no declared dispersion names" in dc.check([g], extra).structural_errors[0]
    assert "not in the family's vocabulary" in dc.check([g], ok, {"a": 2.0, "c": 1}).errors[0]
    flat = _records(50, **{"disp.a": np.full(50, 0.25)})
    assert "zero spread" in dc.check([g], flat).structural_errors[0]
    u = dc.Declared("a", dc.Uniform(-1.0, 1.0))
    wide = _records(50, **{"disp.a": rng.uniform(-1.2, 1.2, 50)})
    assert "outside [-1, 1]" in dc.check([u], wide).structural_errors[0]
    third = dc.Declared("a", dc.Uniform(-1.0, 1.0), period=3, phase=1)
    vals = [float(v) if i % 3 == 1 else None for i, v in enumerate(rng.uniform(-1, 1, 30))]
    assert dc.check([third], _records(30, **{"disp.a": vals})).ok
    vals[0] = 0.5
    assert "does not apply" in dc.check([third], _records(30, **{"disp.a": vals})).structural_errors[0]
    gaps = _records(50, **{"disp.a": [None] + list(rng.normal(0, 2.0, 49))})
    assert "did not fail" in dc.check([g], gaps).structural_errors[0]
    gaps[0]["failure"] = "truth: impact before the first draw"
    assert dc.check([g], gaps).ok
    c = dc.Declared("a", dc.Constant(0.0))
    assert dc.check([c], _records(4, **{"disp.a": [0.0] * 4})).ok
    assert "not as stated" in dc.check([c], _records(4, **{"disp.a": [0, 0, 1e-9, 0]})).structural_errors[0]
    cyc = dc.Declared("a", dc.Cycle((5.0, 10.0)))
    assert dc.check([cyc], _records(4, **{"disp.a": [5.0, 10.0, 5.0, 10.0]})).ok
    assert not dc.check([cyc], _records(4, **{"disp.a": [5.0, 10.0, 10.0, 5.0]})).ok


@pytest.mark.req("OGK-HAR-016")
def test_the_distribution_tests_have_their_stated_size_and_power():
    """Size: 400 correct campaigns of 200 Gaussian runs and of 12 runs (the few-runs case) are
    flagged at most 3 times each (family-wise alpha 1e-3: 0.4 expected; P(>= 4) < 1e-3). Power:
    sigma off by 15 % on 2000 runs, a mean offset of 0.3 sigma on 400, a uniform drawn on half its
    range on 100, a vector with one component at twice its sigma: all flagged."""
    rng = np.random.default_rng(7)
    g = dc.Declared("a", dc.Gaussian(3.0))
    for n in (200, 12):
        flagged = sum(not dc.check([g], _records(n, **{"disp.a": rng.normal(0, 3.0, n)})).ok
                      for _ in range(400))
        assert flagged <= 3, (n, flagged)
    assert dc.check([g], _records(2000, **{"disp.a": rng.normal(0, 3.45, 2000)})).statistical_failures
    assert dc.check([g], _records(400, **{"disp.a": rng.normal(0.9, 3.0, 400)})).statistical_failures
    u = dc.Declared("a", dc.Uniform(0.0, 2.0))
    assert dc.check([u], _records(100, **{"disp.a": rng.uniform(0, 1, 100)})).statistical_failures
    v = dc.Declared("v", dc.Gaussian(1.0), size=3)
    cols = {f"disp.v[{i}]": rng.normal(0, 2.0 if i == 1 else 1.0, 500) for i in range(3)}
    assert dc.check([v], _records(500, **cols)).statistical_failures
    clip = dc.Declared("c", dc.Gaussian(1 / 3, clip=(-1.0, 1.0)))
    xs = np.clip(rng.normal(0, 1 / 3, 3000), -1, 1)
    assert dc.check([clip], _records(3000, **{"disp.c": xs})).ok
    assert not dc.check([clip], _records(3000, **{"disp.c": np.clip(rng.normal(0, 0.4, 3000),
                                                                      -1, 1)})).ok


@pytest.mark.req("OGK-HAR-016", "OGK-HAR-002")
def test_ogk_mc_reports_the_check_and_exits_1_when_a_dispersion_is_not_applied(
        tmp_path, capsys, monkeypatch):
    """`ogk mc` (in process, the command's own code): the dispersions line in the report and
    `dispersion_check` in the envelope, and the same line from `ogk report`; with the radius sigma
    forgotten, the error line and exit 1."""
    import json

    from ogk.sil import command
    header = read_header(resolve_scenario("leo-geo"))
    fam = registry.family(header)

    def mc(out: Path) -> int:
        args = command.parser_for(fam, "ogk mc", header).parse_args(
            ["--runs", "8", "--seed", "3", "--guidance", "nominal", "--truth", "point-mass",
             "--json", str(out)])
        return command.fly(fam, header, args)

    rc = mc(tmp_path / "ok.json")
    text = capsys.readouterr().out
    doc = json.loads((tmp_path / "ok.json").read_text())
    assert "dispersions: 16 keys of [dispersions]: 12 applied with spread > 0" in text
    assert doc["dispersion_check"]["ok"] and rc == (1 if doc["failures"] else 0)
    from ogk.cli.campaign_flow import report        # `ogk report`: the verdict from the table
    assert report(str(tmp_path / "ok.json")) == rc
    assert "dispersions: 16 keys of [dispersions]: 12 applied" in capsys.readouterr().out
    _forget(monkeypatch, "leo_geo")
    rc = mc(tmp_path / "bad.json")
    text = capsys.readouterr().out
    doc = json.loads((tmp_path / "bad.json").read_text())
    assert rc == 1 and "error: initial_state.radius_m: zero spread" in text
    assert doc["dispersion_check"]["errors"] and not doc["dispersion_check"]["ok"]
