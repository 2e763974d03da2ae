"""One family interface (issue 33): every family of ogk.missions.registry, and the test family of
point_mass_family.py, implements every verb of ogk.sil.family.MissionFamily with the protocol's
signature; its optional capabilities are explicit (has_tables, targets, run_aliases, fixed_lists),
never found by getattr; no family keeps a second public face (an adapter module, an alias module)."""
from __future__ import annotations

import inspect
import re
from pathlib import Path

import pytest

from ogk.missions import registry
from ogk.sil.family import FamilyDefaults, MissionFamily
from ogk.sil.pil import TARGETS

import point_mass_family

pytestmark = pytest.mark.req("OGK-HAR-021")

ROOT = Path(__file__).resolve().parents[2]
FAMILIES = {name: registry.family_named(name) for name in registry.PACKAGES}
FAMILIES[point_mass_family.MISSION] = point_mass_family.FAMILY

#: the protocol's verbs (methods) and attributes, read from the protocol itself
VERBS = sorted(n for n, v in vars(MissionFamily).items()
               if callable(v) and not n.startswith("_"))
ATTRIBUTES = sorted(n for n, v in vars(MissionFamily).items() if isinstance(v, property))


def _parameters(function: object) -> list[str]:
    return list(inspect.signature(function).parameters)   # type: ignore[arg-type]


def test_the_protocol_names_every_verb_of_the_issue() -> None:
    assert set(VERBS) >= {"load", "default_runs", "add_campaign_arguments", "plan", "report",
                          "plots", "add_tables_arguments", "tables", "add_run_arguments", "run",
                          "flight_config", "flight_program", "target_job", "target_bounds",
                          "on_target"}
    assert set(ATTRIBUTES) == {"name", "laws", "campaign_doc", "targets", "fixed_lists",
                               "run_aliases", "has_tables"}


@pytest.mark.parametrize("name", sorted(FAMILIES))
def test_every_family_implements_every_verb_with_the_protocols_signature(name: str) -> None:
    fam = FAMILIES[name]
    assert isinstance(fam, MissionFamily) and isinstance(fam, FamilyDefaults)
    assert fam.name == name
    for verb in VERBS:
        mine = getattr(type(fam), verb)
        assert _parameters(mine) == _parameters(getattr(MissionFamily, verb)), (name, verb)
    assert fam.laws and all(isinstance(law, str) for law in fam.laws)
    assert isinstance(fam.campaign_doc, str) and fam.campaign_doc
    assert "host" in fam.targets and set(fam.targets) <= set(TARGETS)
    assert isinstance(fam.fixed_lists, bool) and isinstance(fam.has_tables, bool)
    assert all(isinstance(a, str) and a not in ("tables", "run", "mc") for a in fam.run_aliases)


@pytest.mark.parametrize("name", sorted(FAMILIES))
def test_a_capability_is_declared_exactly_when_it_is_implemented(name: str) -> None:
    """has_tables when `tables` is the family's own; a target beyond the host when its flight
    program and target job are; `run` is every family's own."""
    cls = type(FAMILIES[name])

    def own(verb: str) -> bool:
        return getattr(cls, verb) is not getattr(FamilyDefaults, verb)
    assert own("tables") == own("add_tables_arguments") == cls.has_tables, name
    on_target = set(cls.targets) != {"host"}
    assert (own("flight_config") == own("flight_program") == own("target_job")
            == own("target_bounds") == on_target), name
    assert own("run") and own("add_run_arguments") and own("plan") and own("report"), name


def test_no_verb_is_found_by_getattr_and_no_second_face_is_left() -> None:
    """The engine, the CLI and the registry reach a family by its protocol only; no adapter.py, no
    alias module, no getattr/hasattr on a family object."""
    harness = ROOT / "harness" / "ogk"
    probe = re.compile(r"\b(getattr|hasattr)\((fam|family|adapter|FAMILY|self\.family)\b")
    for path in harness.rglob("*.py"):
        text = path.read_text()
        assert not probe.search(text), path
    missions = harness / "missions"
    assert not list(missions.glob("*/adapter.py"))
    assert not list(missions.glob("*/campaign.py"))


def test_a_family_is_one_registry_line() -> None:
    for name, module in registry.PACKAGES.items():
        assert module == f"ogk.missions.{module.split('.')[2]}.family", name
