"""Scenario files: where they are, what they are, and a typed reader whose every complaint names
the file, the key and the reason (`OgkInputError`).

A scenario is a TOML file under scenarios/ (the wheel ships them as package data) or anywhere, by
path. Every family's file starts with the same header (docs/guides/adding-a-mission.md, "The scenario header")::

    schema = "ogk.orbit-injection/1"   # "ogk.<mission>/<version>": checked against `mission`
    mission = "orbit-injection"        # family: truth model, ground tools, SIL adapter
    name = "leo_geo"
    [guidance]
    law = "vtd-nog"
    [dispersions]                      # what a campaign draws at random, and only that
    [acceptance]                       # the failure criterion (each family states its default)
    [paper_results]                    # optional: the paper's figures, for comparison only

`read_header` checks the schema against the mission and refuses an older spelling of the header
(`OLD_SPELLINGS`) with one line naming the key and what to rename it to, before anything is
computed. Each family's loader reads the rest with `Section`, which rejects missing keys, wrong
types and unknown keys, so a typo never silently falls back to a default.
"""
from __future__ import annotations

import dataclasses
import hashlib
import math
import re
import tomllib
from pathlib import Path
from typing import Any

from ogk_bindings.errors import OgkInputError

# the shipped scenarios and where products go: the repository's, or the wheel's and the current directory
from .paths import SCENARIO_DIR, WORK_ROOT

#: Older spellings kept working (README): `ogk mpsp apophis`, `ogk mc leo-geo`.
ALIASES = {"apophis": "apophis_cubesat", "leo-geo": "leo_geo"}

_MISSING = object()


def resolve_scenario(name_or_path: str | Path) -> Path:
    """A path to an existing file, or the name of a shipped scenario (`leo-geo`, `leo_geo`, `apophis`):
    a file of the repository's scenarios/, or of the wheel's copy of them (ogk_host.paths)."""
    text = str(name_or_path)
    path = Path(text).expanduser()
    if path.suffix == ".toml" or "/" in text:
        if not path.is_file():
            raise OgkInputError("no such scenario file", path=path)
        return path.resolve()
    stem = ALIASES.get(text, text.replace("-", "_"))
    candidate = SCENARIO_DIR / f"{stem}.toml"
    if candidate.is_file():
        return candidate
    known = ", ".join(sorted(p.stem for p in SCENARIO_DIR.glob("*.toml")))
    raise OgkInputError(f"no scenario named {text!r} (scenarios/: {known}; or give a .toml path)")


def read_toml(path: str | Path) -> dict[str, Any]:
    """The parsed file; a missing or malformed file is one line."""
    p = Path(path)
    try:
        with open(p, "rb") as stream:
            return tomllib.load(stream)
    except FileNotFoundError:
        raise OgkInputError("no such scenario file", path=p) from None
    except IsADirectoryError:
        raise OgkInputError("is a directory, not a scenario file", path=p) from None
    except tomllib.TOMLDecodeError as exc:
        raise OgkInputError(f"malformed TOML: {exc}", path=p) from None


def file_sha256(path: str | Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


#: The mission families (one package each in ogk_host and ogk.missions; ogk.missions.registry
#: maps them to their code, test_scenario_header checks the two lists agree).
MISSIONS = ("orbit-injection", "low-thrust-transfer", "low-thrust-rendezvous", "binary-asteroid",
            "proximity-approach")

HEADER_DOC = 'docs/guides/adding-a-mission.md, "The scenario header"'

#: Older spellings of the header, refused with what to rename them to: (missions, dotted key as a
#: regular expression, the new spelling with the key's groups as {0}, {1}). Checked on every table
#: and key of the file, innermost first, so the line names the most precise key.
OLD_SPELLINGS: tuple[tuple[tuple[str, ...], str, str], ...] = (
    (MISSIONS, r"reference\.([^.]+)", "[paper_results.{0}]"),
    (MISSIONS, r"reference", "[paper_results]"),
    (("low-thrust-transfer",), r"perturbations\.(initial|terminal|thrust)", "[dispersions.{0}]"),
    (("low-thrust-transfer",), r"perturbations", "[dispersions] (initial, terminal, thrust)"),
    (("low-thrust-rendezvous",), r"perturbations\.(thrust_angle_sigma_rad|thrust_angle_draw_period_s)",
     "[dispersions] {0}"),
    (("low-thrust-rendezvous",), r"(problem|perturbations|convergence)\.mars_([^.]+)",
     "[{0}] target_{1} (and name the target: [target] name = \"Mars\")"),
    (("binary-asteroid",), r"transfers\.([^.]+)\.paper_([^.]+)", "[paper_results.transfers.{0}] {1}"),
    (("binary-asteroid",), r"monte_carlo\.paper_converged_percent",
     "[paper_results.table3] converged_percent (with levels_percent, the paper's levels)"),
    (("binary-asteroid",), r"monte_carlo\.(levels_percent|sigma_fraction)", "[dispersions] {0}"),
)

#: schema values of the family dialects before the common header (issue 18)
OLD_SCHEMAS = ("ogk.leo_geo/1", "ogk.binary/1", "ogk.rendezvous/1")

_SCHEMA_RE = re.compile(r"ogk\.([a-z0-9-]+)/([1-9][0-9]*)")


def schema_of(mission: str, version: int = 1) -> str:
    """The header's schema value of a family: "ogk.<mission>/<version>"."""
    return f"ogk.{mission}/{version}"


def _keys_innermost_first(table: dict[str, Any], prefix: str = "") -> list[str]:
    out: list[str] = []
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.extend(_keys_innermost_first(value, f"{name}."))
        out.append(name)
    return out


def refuse_old_spellings(raw: dict[str, Any], path: str | Path, mission: str) -> None:
    """One line naming the first key spelt the old way and what to rename it to."""
    for key in _keys_innermost_first(raw):
        for missions, pattern, new in OLD_SPELLINGS:
            match = re.fullmatch(pattern, key)
            if mission in missions and match:
                raise OgkInputError(f"old spelling: rename it to {new.format(*match.groups())} "
                                    f"({HEADER_DOC})", path=path, key=key)


def check_header(raw: dict[str, Any], path: str | Path, schema: str | None = None) -> tuple[str, str]:
    """(mission, schema) of a parsed scenario, checked: `mission` one of MISSIONS, no old spelling,
    `schema` = "ogk.<mission>/<version>" (and equal to `schema` when the family's loader gives its
    own). Every complaint one line, before anything is computed."""
    top = Section(raw, path, "")
    mission = top.text("mission")
    if mission not in MISSIONS:
        raise top.error("mission", f"unknown mission family {mission!r} (known: "
                        f"{', '.join(sorted(MISSIONS))})")
    refuse_old_spellings(raw, path, mission)
    expected = schema or schema_of(mission)
    if not top.has("schema"):
        raise top.error("schema", f"missing key: the header starts with schema = \"{expected}\" "
                        f"({HEADER_DOC})")
    value = top.text("schema")
    match = _SCHEMA_RE.fullmatch(value)
    if value in OLD_SCHEMAS:
        raise top.error("schema", f"old spelling {value!r}: rename it to \"{expected}\" ({HEADER_DOC})")
    if match is None or match.group(1) != mission:
        raise top.error("schema", f"{value!r} is not the schema of mission = \"{mission}\": rename it "
                        f"to \"{expected}\" ({HEADER_DOC})")
    if schema is not None and value != schema:
        raise top.error("schema", f"{value!r}: this version of ogk reads \"{schema}\"")
    return mission, value


@dataclasses.dataclass(frozen=True)
class ScenarioHeader:
    """What every scenario says about itself."""

    path: Path
    sha256: str          #: of the file's bytes: the provenance key of its tables and campaigns
    name: str
    mission: str         #: family, e.g. "orbit-injection"
    law: str             #: guidance law, e.g. "vtd-nog"
    schema: str = ""     #: "ogk.<mission>/<version>"


def read_header(path: str | Path) -> ScenarioHeader:
    p = Path(path)
    raw = read_toml(p)
    mission, schema = check_header(raw, p)
    top = Section(raw, p, "")
    guidance = top.section("guidance")
    return ScenarioHeader(path=p, sha256=file_sha256(p), name=top.text("name"),
                          mission=mission, law=guidance.text("law"), schema=schema)


class Section:
    """One TOML table of a scenario file, read key by key with types and ranges checked.

    `finish()` rejects keys that were never read (typos, keys of another schema)."""

    def __init__(self, data: Any, path: str | Path, prefix: str) -> None:
        if not isinstance(data, dict):
            raise OgkInputError("must be a table", path=path, key=prefix or "(top level)")
        self._data: dict[str, Any] = data
        self._path = Path(path)
        self._prefix = prefix
        self._read: set[str] = set()

    def key(self, name: str) -> str:
        return f"{self._prefix}.{name}" if self._prefix else name

    def error(self, name: str, reason: str) -> OgkInputError:
        return OgkInputError(reason, path=self._path, key=self.key(name))

    def has(self, name: str) -> bool:
        return name in self._data

    def _get(self, name: str, default: Any) -> Any:
        self._read.add(name)
        if name in self._data:
            return self._data[name]
        if default is _MISSING:
            raise self.error(name, "missing key")
        return default

    def section(self, name: str, optional: bool = False) -> "Section":
        value = self._get(name, {} if optional else _MISSING)
        if not isinstance(value, dict):
            raise self.error(name, f"must be a table, got {type(value).__name__}")
        return Section(value, self._path, self.key(name))

    def raw_table(self, name: str) -> dict[str, Any] | None:
        """The TOML table `name` as parsed (marked read; its keys are the caller's to check), or
        None when the file has none (e.g. an optional [paper_results])."""
        if name not in self._data:
            self._read.add(name)
            return None
        self.section(name)
        return self._data[name]

    def number(self, name: str, default: Any = _MISSING, *, positive: bool = False,
               nonnegative: bool = False, lo: float | None = None, hi: float | None = None) -> float:
        value = self._get(name, default)
        if value is None:
            return value  # an optional key left out (default None)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(name, f"must be a number, got {type(value).__name__} {value!r}")
        x = float(value)
        if not math.isfinite(x):
            raise self.error(name, f"must be finite, got {x}")
        if positive and not x > 0.0:
            raise self.error(name, f"must be > 0, got {x:g}")
        if nonnegative and not x >= 0.0:
            raise self.error(name, f"must be >= 0, got {x:g}")
        if lo is not None and x < lo:
            raise self.error(name, f"must be >= {lo:g}, got {x:g}")
        if hi is not None and x > hi:
            raise self.error(name, f"must be <= {hi:g}, got {x:g}")
        return x

    def integer(self, name: str, default: Any = _MISSING, *, lo: int | None = None,
                hi: int | None = None) -> int:
        value = self._get(name, default)
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(name, f"must be an integer, got {type(value).__name__} {value!r}")
        if lo is not None and value < lo:
            raise self.error(name, f"must be >= {lo}, got {value}")
        if hi is not None and value > hi:
            raise self.error(name, f"must be <= {hi}, got {value}")
        return value

    def text(self, name: str, default: Any = _MISSING, choices: tuple[str, ...] | None = None) -> str:
        value = self._get(name, default)
        if not isinstance(value, str):
            raise self.error(name, f"must be a string, got {type(value).__name__} {value!r}")
        if choices is not None and value not in choices:
            raise self.error(name, f"must be one of {', '.join(choices)}; got {value!r}")
        return value

    def flag(self, name: str, default: Any = _MISSING) -> bool:
        value = self._get(name, default)
        if not isinstance(value, bool):
            raise self.error(name, f"must be true or false, got {value!r}")
        return value

    def numbers(self, name: str, length: int | None = None, default: Any = _MISSING) -> tuple[float, ...]:
        value = self._get(name, default)
        if value is None:
            return value
        if not isinstance(value, list) or any(isinstance(v, bool) or not isinstance(v, (int, float))
                                              for v in value):
            raise self.error(name, f"must be a list of numbers, got {value!r}")
        if length is not None and len(value) != length:
            raise self.error(name, f"must have {length} entries, got {len(value)}")
        return tuple(float(v) for v in value)

    def dataclass(self, cls: type, **checks: dict[str, Any]) -> Any:
        """Builds `cls` from the scalar keys named like its fields (all numbers unless the field's
        annotation says int / bool / str); `checks` maps a field to `number()` range options."""
        values: dict[str, Any] = {}
        for f in dataclasses.fields(cls):
            kind = str(f.type)
            opts = checks.get(f.name, {})
            if kind == "int":
                values[f.name] = self.integer(f.name, **opts)
            elif kind == "bool":
                values[f.name] = self.flag(f.name, **opts)
            elif kind == "str":
                values[f.name] = self.text(f.name, **opts)
            else:
                values[f.name] = self.number(f.name, **opts)
        return cls(**values)

    def finish(self) -> None:
        unknown = sorted(set(self._data) - self._read)
        if unknown:
            raise self.error(unknown[0], "unknown key" + (f" (also {', '.join(unknown[1:])})"
                                                          if len(unknown) > 1 else ""))


TABLE_ROOT = WORK_ROOT / "build" / "tables"


def table_dir_for(path: str | Path, root: str | Path | None = None) -> Path:
    """Where the ground products of a scenario file live by default:
    `build/tables/<name>-<first 12 hex of the file's SHA-256>` under the repository root (under the
    current directory when ogk runs from an installed wheel: ogk_host.paths.WORK_ROOT), so two
    scenarios, or two versions of one, never share a directory."""
    header = read_header(path)
    return Path(TABLE_ROOT if root is None else root) / f"{header.name}-{header.sha256[:12]}"
