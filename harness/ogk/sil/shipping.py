"""What a campaign sends to a worker on another machine (docs/guides/scale-out.md), and how the worker
rebuilds the plan from it: the engine-level half of the Dask executor (ogk.sil.dask_executor).

A `Shipment` carries everything a run depends on besides its id and seed, as data:
  * the family's campaign contract (its FAMILY object, pickled by reference to its class),
  * the scenario file's bytes and SHA-256, and the plan's options (JSON) and products (SHA-256s),
  * the ground products' files with their SHA-256: every file of each directory that an option or a
    product names by an absolute path (a file: its directory), e.g. the NOG tables, the MPSP nominal
    and its manifest (the families name their default product directories absolutely).
A path under the client's repository travels relative to it and lands under the worker's; any
other path lands where it is on the client (a shared or identical path on a cluster).

On the worker (`plan_of`): the worker's numerics fingerprint (ogk.sil.numerics) must equal the
client's, or the chunk is refused (OgkInputError naming what differs): the records would not be the
local executor's bit for bit. Then each file present is checked against its SHA-256 and a missing one is
written (atomically) and checked again; a copy that differs is refused (OgkInputError, one line
naming the file), never overwritten. Then the family rebuilds the plan from the scenario and the
options, exactly as `ogk replay` does (ogk.cli.campaign_flow), and the rebuilt plan's scenario
SHA-256 and products must equal the shipped ones: the worker flies the client's campaign or
nothing. The plan is built once per worker process and shipment (cached by `Shipment.key`).
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ogk_bindings.errors import OgkInputError
from ogk_host.scenario_file import read_header

from . import numerics, precision
from .family import CampaignPlan, MissionFamily
from .pil_build import ROOT

#: the most bytes of ground products one shipment may carry (they go to every worker once)
MAX_SHIPPED_BYTES = 64 * 1024 * 1024
#: plans kept per worker process (one per campaign; a target campaign and its host twin are two)
PLAN_CACHE = 4


@dataclasses.dataclass(frozen=True)
class ShippedFile:
    """One file: where it lands (relative to the repository, or absolute), SHA-256, bytes."""

    path: str
    relative: bool
    sha256: str
    data: bytes

    def local_path(self) -> Path:
        return ROOT / self.path if self.relative else Path(self.path)


@dataclasses.dataclass(frozen=True)
class Shipment:
    """A campaign plan as data (module doc)."""

    family: MissionFamily
    scenario: ShippedFile
    options: dict[str, Any]
    products: dict[str, Any]
    files: tuple[ShippedFile, ...]
    client_root: str
    numerics: dict[str, str] = dataclasses.field(default_factory=dict)  #: the client's (ogk.sil.numerics)

    @property
    def key(self) -> str:
        """SHA-256 of what the plan depends on: the worker's plan cache key."""
        doc = {"family": self.family.name, "scenario": self.scenario.sha256,
               "options": self.options, "products": self.products,
               "files": sorted((f.path, f.sha256) for f in self.files)}
        return hashlib.sha256(json.dumps(doc, sort_keys=True).encode()).hexdigest()

    @property
    def shipped_bytes(self) -> int:
        return len(self.scenario.data) + sum(len(f.data) for f in self.files)


def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _file(path: Path) -> ShippedFile:
    data = path.read_bytes()
    resolved = path.resolve()
    try:
        return ShippedFile(str(resolved.relative_to(ROOT)), True, _sha256(data), data)
    except ValueError:
        return ShippedFile(str(resolved), False, _sha256(data), data)


def _product_paths(values: Mapping[str, Any]) -> list[Path]:
    """The existing absolute paths named by string values (a file stands for its directory)."""
    out = []
    for value in values.values():
        if not isinstance(value, str) or not value.startswith(os.sep) or len(value) > 4096:
            continue
        p = Path(value)
        if p.is_file():
            out.append(p.parent)
        elif p.is_dir():
            out.append(p)
    return out


def _directory_files(directory: Path) -> list[Path]:
    """Every regular file under `directory`, dot files (locks, stamps) left out."""
    return sorted(p for p in directory.rglob("*") if p.is_file()
                  and not any(part.startswith(".") for part in p.relative_to(directory).parts))


def ship(plan: CampaignPlan, family: MissionFamily) -> Shipment:
    """The shipment of `plan` (module doc). Raises OgkInputError when the products are too big."""
    files: dict[str, ShippedFile] = {}
    for directory in _product_paths({**plan.options, **plan.products}):
        for p in _directory_files(directory):
            f = _file(p)
            files[f.path] = f
    shipment = Shipment(family=family, scenario=_file(Path(plan.scenario_path)),
                        options=json.loads(json.dumps(plan.options)),
                        products=json.loads(json.dumps(plan.products)),
                        files=tuple(files[k] for k in sorted(files)), client_root=str(ROOT),
                        numerics=numerics.fingerprint())
    if shipment.shipped_bytes > MAX_SHIPPED_BYTES:
        raise OgkInputError(f"the ground products weigh {shipment.shipped_bytes} bytes, more than "
                            f"the {MAX_SHIPPED_BYTES} a shipment carries", key="--dask")
    return shipment


def materialise(f: ShippedFile) -> Path:
    """The file on this machine, checked by its SHA-256 (written when missing; module doc)."""
    if _sha256(f.data) != f.sha256:
        raise OgkInputError(f"shipped bytes do not match their SHA-256 {f.sha256[:12]}",
                            path=f.path, key="--dask")
    path = f.local_path()
    if not path.exists():
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_name(f".{path.name}.{os.getpid()}.ship")
        tmp.write_bytes(f.data)
        os.replace(tmp, path)
    if _sha256(path.read_bytes()) != f.sha256:
        raise OgkInputError(f"this worker's copy differs from the campaign's (SHA-256 "
                            f"{f.sha256[:12]}): remove it or give the worker the same file",
                            path=path, key="--dask")
    return path


def relocate(value: Any, client_root: str) -> Any:
    """A path under the client's repository as the same path under this worker's."""
    if isinstance(value, str) and client_root != str(ROOT):
        if value == client_root or value.startswith(client_root + os.sep):
            return str(ROOT) + value[len(client_root):]
    return value


_PLANS: dict[str, CampaignPlan] = {}


def plan_of(shipment: Shipment) -> CampaignPlan:
    """The campaign's plan on this worker: products checked or written, plan rebuilt by the family
    and checked against the shipment (module doc); built once per process and shipment."""
    # checked before the plan cache: the key leaves the client's numerics out
    differ = numerics.differences(numerics.fingerprint(), shipment.numerics)
    if differ:
        raise OgkInputError("this worker's numerics differ from the client's, so its records would "
                            "not be bit for bit the local campaign's (" + "; ".join(differ) + "): "
                            "run the workers on the client's CPU kind and packages, or set "
                            "OPENBLAS_CORETYPE and NPY_DISABLE_CPU_FEATURES alike everywhere "
                            "(docs/guides/scale-out.md)", key="--dask")
    precision.check_options(shipment.options)   # the worker loaded the campaign's kernel precision
    key = shipment.key
    plan = _PLANS.get(key)
    if plan is not None:
        return plan
    scenario = materialise(shipment.scenario)
    for f in shipment.files:
        materialise(f)
    options = {k: relocate(v, shipment.client_root) for k, v in shipment.options.items()}
    plan = shipment.family.plan(read_header(scenario), options)
    want = {k: relocate(v, shipment.client_root) for k, v in shipment.products.items()}
    if plan.scenario_sha256 != shipment.scenario.sha256:
        raise OgkInputError("the worker read another scenario (SHA-256 differs)", path=scenario,
                            key="--dask")
    if plan.products != want:
        diff = sorted(k for k in set(plan.products) | set(want)
                      if plan.products.get(k) != want.get(k))
        raise OgkInputError(f"this worker's ground products differ from the campaign's "
                            f"({', '.join(diff)})", path=scenario, key="--dask")
    while len(_PLANS) >= PLAN_CACHE:
        _PLANS.pop(next(iter(_PLANS)))
    _PLANS[key] = plan
    return plan
