"""Scenario files: where they are, what they are, and a typed reader whose every complaint names
the file, the key and the reason (`OgkInputError`).

A scenario is a TOML file under scenarios/ (or anywhere, by path). Its top level says which
mission family and which guidance law it is::

    mission = "orbit-injection"        # family: truth model, ground tools, SIL adapter
    [guidance]
    law = "vtd-nog"

Each family's loader reads the rest with `Section`, which rejects missing keys, wrong types and
unknown keys, so a typo never silently falls back to a default (docs/adding-a-mission.md).
"""
from __future__ import annotations

import dataclasses
import hashlib
import math
import tomllib
from pathlib import Path
from typing import Any

from ogk_bindings.errors import OgkInputError

REPO_ROOT = Path(__file__).resolve().parents[2]
SCENARIO_DIR = REPO_ROOT / "scenarios"

#: Older spellings kept working (README): `ogk mpsp apophis`, `ogk mc leo-geo`.
ALIASES = {"apophis": "apophis_cubesat", "leo-geo": "leo_geo"}

_MISSING = object()


def resolve_scenario(name_or_path: str | Path) -> Path:
    """A path to an existing file, or a name under scenarios/ (`leo-geo`, `leo_geo`, `apophis`)."""
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


@dataclasses.dataclass(frozen=True)
class ScenarioHeader:
    """What every scenario says about itself."""

    path: Path
    sha256: str          #: of the file's bytes: the provenance key of its tables and campaigns
    name: str
    mission: str         #: family, e.g. "orbit-injection"
    law: str             #: guidance law, e.g. "vtd-nog"


def read_header(path: str | Path) -> ScenarioHeader:
    p = Path(path)
    raw = read_toml(p)
    top = Section(raw, p, "")
    guidance = top.section("guidance")
    return ScenarioHeader(path=p, sha256=file_sha256(p), name=top.text("name"),
                          mission=top.text("mission"), law=guidance.text("law"))


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


TABLE_ROOT = REPO_ROOT / "build" / "tables"


def table_dir_for(path: str | Path, root: str | Path | None = None) -> Path:
    """Where the ground products of a scenario file live by default:
    `build/tables/<name>-<first 12 hex of the file's SHA-256>` under the repository root, so two
    scenarios, or two versions of one, never share a directory."""
    header = read_header(path)
    return Path(TABLE_ROOT if root is None else root) / f"{header.name}-{header.sha256[:12]}"
