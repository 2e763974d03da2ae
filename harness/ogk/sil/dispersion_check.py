"""Dispersions proven applied (issue 23, after AVSLab/basilisk issue 1164): a campaign's per-run
records checked against the scenario's `[dispersions]`, the same way for every mission family.

Naming rule (every family): a record carries the value of each declared dispersion *as applied to
the run* under `disp.<key>`, <key> the dotted key of the scenario's `[dispersions]` table
(`disp.initial_state.radius_m`, `disp.thrust_angle_sigma_rad`); a vector declared by one key
(eq. 55's coefficients, a terminal offset) under `disp.<key>[i]`, i = 0, 1, ...; `None` on a run
the dispersion does not apply to (another kind of case) or a run that failed before the draw.

A family maps its `[dispersions]` table to a tuple of `Declared` (its vocabulary, in its
dispersions.py): one per key of the table, each with a distribution below, or a `Parameter` (a key
that shapes another dispersion and is not drawn itself: a vector's size, a draw period).

The check (`check`), per declared dispersion:
  structural (an error: `ogk mc` exits 1; deterministic, a bug whatever the seed):
    - every scenario key named by one declaration, every `disp.*` record key declared;
    - its record keys present in every record, a finite value on every run it applies to (None
      only on a run that failed), None on the others;
    - random kinds: spread > 0 over the runs (>= 2 values), values inside the stated support
      (uniform range, clipping bounds);
    - exact kinds (constant, cycle over the runs, listed cases): every value as stated;
  statistical (random kinds; at family-wise significance ALPHA, Bonferroni over the tests made):
    - Kolmogorov-Smirnov of the probability-integral transforms F_c(x) of every component against
      U(0, 1) (scipy's exact small-sample distribution: valid for a few runs as for many);
    - Gaussian without clipping: the moments, exact for any number of runs: the mean,
      sqrt(n) (mean - mu) / sigma ~ N(0, 1), and the variance, sum((x - mu)^2) / sigma^2 ~
      chi^2(n), both two-sided (they have power on a few runs where KS has little).
  A statistical failure is a warning in `ogk mc` (a correct campaign fails it with probability
  ALPHA), a failure in the test suite (fixed seeds: deterministic).
"""
from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

PREFIX = "disp."
#: family-wise significance of the statistical tests of one check (Bonferroni over its tests)
ALPHA = 1.0e-3
#: exact kinds (cycle, listed): |value - stated| <= EXACT_TOL max(1, |stated|) (values recovered
#: from the applied problem carry rounding)
EXACT_TOL = 1.0e-9


@dataclasses.dataclass(frozen=True)
class Gaussian:
    """N(mean, sigma^2), optionally clipped to [clip[0], clip[1]] (the clipped mass sits on the
    bounds)."""

    sigma: float
    mean: float = 0.0
    clip: tuple[float, float] | None = None

    def describe(self) -> str:
        c = "" if self.clip is None else f" clipped to [{self.clip[0]:g}, {self.clip[1]:g}]"
        return f"gaussian mean {self.mean:g} sigma {self.sigma:g}{c}"

    def cdf(self, x: np.ndarray, component: int) -> np.ndarray:
        from scipy.stats import norm
        return np.asarray(norm.cdf(x, loc=self.mean, scale=self.sigma))

    def support(self, component: int) -> tuple[float, float]:
        return self.clip if self.clip is not None else (-math.inf, math.inf)


@dataclasses.dataclass(frozen=True)
class Uniform:
    """U(lo, hi); lo and hi per component for a vector (a box)."""

    lo: float | tuple[float, ...]
    hi: float | tuple[float, ...]

    def _bounds(self, component: int) -> tuple[float, float]:
        lo = self.lo[component] if isinstance(self.lo, tuple) else self.lo
        hi = self.hi[component] if isinstance(self.hi, tuple) else self.hi
        return float(lo), float(hi)

    def describe(self) -> str:
        return f"uniform [{_fmt(self.lo)}, {_fmt(self.hi)}]"

    def cdf(self, x: np.ndarray, component: int) -> np.ndarray:
        lo, hi = self._bounds(component)
        return np.clip((x - lo) / (hi - lo), 0.0, 1.0)

    def support(self, component: int) -> tuple[float, float]:
        return self._bounds(component)


@dataclasses.dataclass(frozen=True)
class Constant:
    """Every run applies exactly `value` (a dispersion declared zero, or switched off)."""

    value: float = 0.0

    def describe(self) -> str:
        return f"constant {self.value:g}"


@dataclasses.dataclass(frozen=True)
class Cycle:
    """Run i applies values[i mod len(values)] (levels flown in turn)."""

    values: tuple[float, ...]

    def describe(self) -> str:
        return f"cycle over {_fmt(self.values)}"


@dataclasses.dataclass(frozen=True)
class Listed:
    """Run first_run + j applies values[j] (a scalar, or one tuple per run for a vector): cases
    flown as listed, nothing drawn."""

    values: tuple[Any, ...]
    first_run: int = 0

    def describe(self) -> str:
        return f"listed, {len(self.values)} cases from run {self.first_run}"


@dataclasses.dataclass(frozen=True)
class Parameter:
    """A key that shapes another declared dispersion (`of`) and is not drawn itself."""

    of: str
    why: str = ""

    def describe(self) -> str:
        return f"parameter of {self.of}" + (f" ({self.why})" if self.why else "")


Distribution = Gaussian | Uniform | Constant | Cycle | Listed | Parameter
RANDOM = (Gaussian, Uniform)


@dataclasses.dataclass(frozen=True)
class Declared:
    """One key of the scenario's [dispersions] and what a run applies of it."""

    key: str                              #: dotted key in [dispersions]
    dist: Distribution
    size: int | None = None               #: None: a scalar; else a vector of `size` components
    period: int = 1                       #: applies to the runs with run_id % period == phase
    phase: int = 0

    @property
    def record_keys(self) -> tuple[str, ...]:
        if isinstance(self.dist, Parameter):
            return ()
        if self.size is None:
            return (PREFIX + self.key,)
        return tuple(f"{PREFIX}{self.key}[{i}]" for i in range(self.size))

    def applies(self, run_id: int) -> bool:
        return run_id % self.period == self.phase

    def describe(self) -> str:
        where = "" if self.period == 1 else f", runs with id mod {self.period} = {self.phase}"
        vec = "" if self.size is None else f", {self.size} components"
        return f"{self.dist.describe()}{vec}{where}"


@dataclasses.dataclass
class Entry:
    """The verdict on one declared dispersion."""

    key: str
    expected: str
    runs: int = 0                         #: runs it applies to
    n: int = 0                            #: values checked (runs x components)
    std: float | None = None              #: sample std of the pooled values
    p_ks: float | None = None
    p_mean: float | None = None
    p_variance: float | None = None
    status: str = ""                      #: tested, exact, too few runs, parameter, error
    errors: list[str] = dataclasses.field(default_factory=list)
    statistical: list[str] = dataclasses.field(default_factory=list)

    def to_json(self) -> dict[str, Any]:
        return dataclasses.asdict(self)


@dataclasses.dataclass
class DispersionCheck:
    """All verdicts of one campaign (module doc); `errors`: the structural ones not tied to a key."""

    entries: list[Entry]
    errors: list[str]
    alpha: float
    tests: int

    @property
    def structural_errors(self) -> list[str]:
        return self.errors + [f"{e.key}: {m}" for e in self.entries for m in e.errors]

    @property
    def statistical_failures(self) -> list[str]:
        return [f"{e.key}: {m}" for e in self.entries for m in e.statistical]

    @property
    def ok(self) -> bool:
        return not self.structural_errors and not self.statistical_failures

    def summary(self) -> str:
        """One line for the campaign report (then one line per problem)."""
        count = {k: sum(1 for e in self.entries if e.status == k)
                 for k in ("tested", "exact", "too few runs", "parameter")}
        head = (f"dispersions: {len(self.entries)} keys of [dispersions]: {count['tested']} "
                f"applied with spread > 0 and the stated distribution ({self.tests} tests, "
                f"family-wise significance {self.alpha:g}), {count['exact']} applied exactly as "
                f"stated, {count['too few runs']} present on fewer than 2 runs (not assessable), "
                f"{count['parameter']} parameters of another")
        if self.ok:
            return head
        lines = [head, f"  {len(self.structural_errors)} errors, "
                 f"{len(self.statistical_failures)} distribution test failures"]
        lines += [f"  error: {m}" for m in self.structural_errors]
        lines += [f"  warning: {m}" for m in self.statistical_failures]
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        return {"ok": self.ok, "alpha": self.alpha, "tests": self.tests,
                "errors": self.structural_errors, "distribution_failures": self.statistical_failures,
                "entries": [e.to_json() for e in self.entries]}


def flatten(table: Mapping[str, Any], prefix: str = "") -> list[str]:
    """The dotted leaf keys of a TOML table (a list of numbers is one leaf)."""
    out: list[str] = []
    for k, v in table.items():
        if isinstance(v, Mapping):
            out += flatten(v, f"{prefix}{k}.")
        else:
            out.append(prefix + k)
    return out


def _fmt(v: Any) -> str:
    if isinstance(v, tuple):
        return "(" + ", ".join(f"{x:g}" for x in v) + ")"
    return f"{v:g}"


def _number(v: Any) -> float | None:
    if v is None or isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
        return None
    x = float(v)
    return x if math.isfinite(x) else None


def _exact(dist: Cycle | Listed | Constant, run_id: int, component: int) -> float | None:
    """The value an exact kind states for run `run_id` (None: no statement for this run)."""
    if isinstance(dist, Constant):
        return dist.value
    if isinstance(dist, Cycle):
        return float(dist.values[run_id % len(dist.values)])
    j = run_id - dist.first_run
    if not 0 <= j < len(dist.values):
        return None
    v = dist.values[j]
    return float(v[component]) if isinstance(v, (tuple, list)) else float(v)


def _collect(d: Declared, records: Sequence[Mapping[str, Any]], entry: Entry
             ) -> tuple[list[int], np.ndarray]:
    """The run ids carrying values and their (runs, components) values; structural errors on
    missing keys, missing values and values where the dispersion does not apply."""
    keys = d.record_keys
    ids: list[int] = []
    rows: list[list[float]] = []
    missing = [k for k in keys if any(k not in r for r in records)]
    if missing:
        entry.errors.append(f"missing from the records: {', '.join(missing[:3])}"
                            + (" ..." if len(missing) > 3 else "")
                            + " (the family does not record what it applies)")
        return ids, np.zeros((0, len(keys)))
    for r in records:
        rid = int(r["run_id"])
        vals = [_number(r[k]) for k in keys]
        applies = d.applies(rid) and not (isinstance(d.dist, Listed) and _exact(d.dist, rid, 0) is None)
        if not applies:
            if any(r[k] is not None and not (isinstance(r[k], float) and math.isnan(r[k]))
                   for k in keys):
                entry.errors.append(f"run {rid}: a value where the dispersion does not apply")
            continue
        entry.runs += 1
        if any(v is None for v in vals):
            if not r.get("failure"):
                entry.errors.append(f"run {rid}: no finite value, and the run did not fail")
            continue
        ids.append(rid)
        rows.append([float(v) for v in vals])   # type: ignore[arg-type]
    return ids, np.array(rows, dtype=np.float64).reshape(len(rows), len(keys))


def _check_exact(d: Declared, ids: list[int], x: np.ndarray, entry: Entry) -> None:
    assert isinstance(d.dist, (Constant, Cycle, Listed))
    bad = []
    for row, rid in enumerate(ids):
        for c in range(x.shape[1]):
            want = _exact(d.dist, rid, c)
            assert want is not None
            tol = 0.0 if isinstance(d.dist, Constant) else EXACT_TOL * max(1.0, abs(want))
            if not abs(x[row, c] - want) <= tol:
                bad.append(f"run {rid}: {d.record_keys[c]} = {x[row, c]:.10g}, stated {want:.10g}")
    if bad:
        entry.errors.append(f"{len(bad)} values not as stated; first: {bad[0]}")


def _check_random(d: Declared, x: np.ndarray, entry: Entry) -> list[tuple[str, float]]:
    """Spread and support (structural); the p-values of the statistical tests to be judged."""
    from scipy import stats
    dist = d.dist
    assert isinstance(dist, RANDOM)
    n_runs, n_comp = x.shape
    entry.n = int(x.size)
    if x.size:
        entry.std = float(np.std(x, ddof=1)) if x.size > 1 else 0.0
    if n_runs < 2:
        return []                  # spread and distribution need two runs
    flat = [k for c, k in enumerate(d.record_keys) if not np.ptp(x[:, c]) > 0.0]
    if flat:
        entry.errors.append(f"zero spread over {n_runs} runs ({', '.join(flat[:3])} = "
                            f"{x[0, d.record_keys.index(flat[0])]:g} in every run): declared "
                            f"{dist.describe()} but not applied")
        return []
    for c in range(n_comp):
        lo, hi = dist.support(c)
        tol = 1e-12 * max(1.0, abs(lo) if math.isfinite(lo) else 1.0,
                          abs(hi) if math.isfinite(hi) else 1.0)
        out = (x[:, c] < lo - tol) | (x[:, c] > hi + tol)
        if out.any():
            entry.errors.append(f"{d.record_keys[c]}: {int(out.sum())} values outside "
                                f"[{lo:g}, {hi:g}] (e.g. {x[out, c][0]:g})")
    if entry.errors:
        return []
    u = np.concatenate([dist.cdf(x[:, c], c) for c in range(n_comp)])
    tests = []
    p = float(stats.kstest(u, "uniform").pvalue)
    entry.p_ks = p
    tests.append(("Kolmogorov-Smirnov against the stated distribution", p))
    if isinstance(dist, Gaussian) and dist.clip is None:
        z = float(np.mean(x) - dist.mean) * math.sqrt(x.size) / dist.sigma
        pm = float(2.0 * stats.norm.sf(abs(z)))
        entry.p_mean = pm
        tests.append((f"mean {np.mean(x):.4g} against {dist.mean:g} (z = {z:.3g}, "
                      f"{x.size} values)", pm))
        chi2 = float(np.sum(((x - dist.mean) / dist.sigma) ** 2))
        dof = x.size
        pv = float(min(1.0, 2.0 * min(stats.chi2.cdf(chi2, dof), stats.chi2.sf(chi2, dof))))
        entry.p_variance = pv
        tests.append((f"variance {np.mean((x - dist.mean) ** 2):.4g} against sigma^2 "
                      f"{dist.sigma ** 2:.4g} (chi-square, {dof} values)", pv))
    return tests


def check(declared: Sequence[Declared], records: Sequence[Mapping[str, Any]],
          table: Mapping[str, Any] | None = None, alpha: float = ALPHA) -> DispersionCheck:
    """Checks `records` (a campaign's rows: run_id, failure, disp.* keys) against the declared
    dispersions; `table`: the scenario's raw [dispersions] table, every key of which must be
    declared (module doc)."""
    errors: list[str] = []
    names = [d.key for d in declared]
    dup = sorted({k for k in names if names.count(k) > 1})
    if dup:
        errors.append(f"declared twice: {', '.join(dup)}")
    if table is not None:
        leaves = flatten(table)
        errors += [f"{k}: in the scenario's [dispersions] but not in the family's vocabulary "
                   "(nothing says how it is applied)" for k in leaves if k not in names]
        errors += [f"{k}: declared by the family but not in the scenario's [dispersions]"
                   for k in names if k not in leaves]
    known = {k for d in declared for k in d.record_keys}
    extra = sorted({k for r in records for k in r if k.startswith(PREFIX) and k not in known})
    if extra:
        errors.append(f"record keys no declared dispersion names: {', '.join(extra[:5])}")
    entries: list[Entry] = []
    pending: list[tuple[Entry, str, float]] = []
    for d in declared:
        entry = Entry(d.key, d.describe())
        entries.append(entry)
        if isinstance(d.dist, Parameter):
            entry.status = "parameter"
            continue
        ids, x = _collect(d, records, entry)
        if not entry.errors:
            if isinstance(d.dist, RANDOM):
                pending += [(entry, what, p) for what, p in _check_random(d, x, entry)]
                entry.status = "tested" if len(ids) >= 2 else "too few runs"
            else:
                entry.n = int(x.size)
                _check_exact(d, ids, x, entry)
                entry.status = "exact"
        if entry.errors:
            entry.status = "error"
    level = alpha / max(len(pending), 1)
    for entry, what, p in pending:
        if p < level:
            entry.statistical.append(f"{what}: p = {p:.3g} < {level:.3g} "
                                     f"({alpha:g} over {len(pending)} tests)")
    return DispersionCheck(entries, errors, alpha, len(pending))


@dataclasses.dataclass(frozen=True)
class Declaration:
    """What a campaign plan states about its dispersions: the scenario's raw [dispersions] table
    and the family's declarations of it (with the command's options applied)."""

    table: Mapping[str, Any]
    declared: tuple[Declared, ...]


def check_plan(plan: Any, records: Sequence[Mapping[str, Any]],
               alpha: float = ALPHA) -> DispersionCheck | None:
    """The check of a campaign plan's records (None when the family declares nothing)."""
    decl: Declaration | None = getattr(plan, "dispersions", None)
    if decl is None:
        return None
    return check(decl.declared, records, decl.table, alpha)


def draw_only(plan: Any, runs: int, seed: int) -> list[dict[str, Any]]:
    """The disp.* records of runs 0..runs-1 drawn without flying (the plan's `draw`: the same
    code the flight's records come from), with run_id, run_seed and failure ""."""
    from .engine import seeds_of
    draw: Callable[..., Sequence[Mapping[str, Any]]] | None = getattr(plan, "draw", None)
    if draw is None:
        raise ValueError(f"the {plan.family} family cannot draw without flying")
    ids = np.arange(runs, dtype=np.int64)
    seeds = seeds_of(seed, ids)
    return [{"run_id": int(i), "run_seed": int(s), "failure": "", **dict(rec)}
            for i, s, rec in zip(ids, seeds, draw(ids, seeds))]


def scenario_table(path: Any) -> dict[str, Any]:
    """The raw [dispersions] table of a scenario file ({} when it has none)."""
    import tomllib
    from pathlib import Path
    with Path(path).open("rb") as f:
        return dict(tomllib.load(f).get("dispersions") or {})
