"""ogk as a package (docs/guides/install.md): the extras' one-line messages, the scenarios resolved from package
data outside the repository, the version from version.h. The wheel itself is built, installed in a clean
venv and flown by `make test-wheel` (tests/wheel/check_wheel.py); here, in seconds:

* `ogk_bindings.extras.need` with the package missing (sys.modules[name] = None, as for an uninstalled
  package): MissingExtra, one line naming the extra; an installed package whose own dependency is
  missing raises its own error; the Basilisk modules and `ogk mc --dask` go through it (the CLI: one
  line, exit 2); no module imports an optional package any other way (ast of every source);
  the extras are pyproject.toml's, and none of their packages is a dependency;
* the packages as a wheel lays them out (ogk, ogk_host with scenarios/ inside, ogk_bindings, copied
  into a site directory, run from another directory): no source tree, every scenario name and each
  family's default scenario resolve to the shipped copy, products go under the current directory,
  `--target m7` says in one line that it needs the repository;
* `ogk.__version__` (the distribution's, setup.py reads version.h) is the compiled kernel's.
"""
from __future__ import annotations

import ast
import os
import shutil
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import pytest
from ogk_bindings.extras import EXTRAS, MissingExtra, need

pytestmark = pytest.mark.req("OGK-HAR-023")

ROOT = Path(__file__).resolve().parents[2]
#: top-level module of each optional distribution (EXTRAS)
OPTIONAL_MODULES = {"Basilisk": "basilisk", "dask": "dask", "distributed": "dask", "daqp": "peers"}


def missing(monkeypatch: pytest.MonkeyPatch, top: str) -> None:
    """`top` and its submodules as if not installed (an import of them raises ModuleNotFoundError)."""
    for name in [m for m in sys.modules if m == top or m.startswith(top + ".")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, top, None)


@pytest.mark.parametrize("module, extra", [("Basilisk.simulation.spacecraft", "basilisk"),
                                           ("distributed", "dask"), ("daqp", "peers")])
def test_missing_extra_is_one_line_naming_it(monkeypatch: pytest.MonkeyPatch, module: str,
                                             extra: str) -> None:
    missing(monkeypatch, module.partition(".")[0])
    with pytest.raises(MissingExtra) as err:
        need(module, extra, "the thing asked for")
    assert err.value.line() == f"ogk[{extra}] is needed for the thing asked for: pip install 'ogk[{extra}]'"
    assert err.value.extra == extra and "\n" not in str(err.value)


def test_installed_extra_is_the_module() -> None:
    import distributed
    assert need("distributed", "dask", "x") is distributed


def test_broken_install_raises_its_own_error(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An installed package that cannot import one of its own dependencies is not a missing extra."""
    (tmp_path / "ogk_fake_peer").mkdir()
    (tmp_path / "ogk_fake_peer" / "__init__.py").write_text("import ogk_no_such_dependency\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    with pytest.raises(ModuleNotFoundError) as err:
        need("ogk_fake_peer", "peers", "x")
    assert not isinstance(err.value, MissingExtra) and err.value.name == "ogk_no_such_dependency"
    with pytest.raises(ValueError, match="no extra 'nope'"):
        need("json", "nope", "x")


def test_basilisk_modules_name_their_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    missing(monkeypatch, "Basilisk")
    # the package and its modules imported again: a test that ran Basilisk before left them loaded,
    # and `from . import injection` takes the loaded package's attribute without importing
    package = "ogk.missions.orbit_injection.basilisk"
    for name in [m for m in sys.modules if m == package or m.startswith(package + ".")]:
        monkeypatch.delitem(sys.modules, name)
    import importlib
    with pytest.raises(MissingExtra, match=r"^ogk\[basilisk\] is needed for the Basilisk .*: "
                                           r"pip install 'ogk\[basilisk\]'$"):
        importlib.import_module("ogk.missions.orbit_injection.basilisk.crosscheck")


def test_dask_option_without_the_extra_is_one_line(monkeypatch: pytest.MonkeyPatch,
                                                   capsys: pytest.CaptureFixture[str],
                                                   tmp_path: Path) -> None:
    """`ogk mc SCENARIO --dask ...` refuses in one line, exit 2, before any ground product is made."""
    from ogk.cli import main
    missing(monkeypatch, "distributed")
    code = main(["mc", "leo-geo", "--runs", "1", "--dask", "local:1", "--json", str(tmp_path / "F.json")])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and err == ["ogk mc: ogk[dask] is needed for ogk mc --dask: pip install 'ogk[dask]'"]
    assert not (tmp_path / "F.json").exists()


def _optional_imports(path: Path) -> list[str]:
    tree = ast.parse(path.read_text(), str(path))
    found = []
    for node in ast.walk(tree):
        names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                 [node.module] if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module
                 else [])
        found += [f"{path.relative_to(ROOT)}:{node.lineno}: {n}" for n in names
                  if n.partition(".")[0] in OPTIONAL_MODULES]
    return found


def test_optional_packages_imported_only_through_need() -> None:
    sources = [p for d in ("harness", "host", "bindings", "tests/bench") for p in (ROOT / d).rglob("*.py")]
    assert sources
    assert [hit for p in sources for hit in _optional_imports(p)] == []


def test_extras_are_pyprojects() -> None:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    extras = {k: v for k, v in project["optional-dependencies"].items() if k != "test"}
    assert {k: tuple(r.split(">")[0].split("=")[0] for r in v) for k, v in extras.items()} == EXTRAS
    assert set(OPTIONAL_MODULES.values()) == set(EXTRAS)
    hard = {r.split(">")[0].split("=")[0].split("[")[0] for r in project["dependencies"]}
    assert hard.isdisjoint({d.split("[")[0] for ds in EXTRAS.values() for d in ds})
    assert "version" in project["dynamic"] and "version" not in project


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The three packages as the wheel lays them out (build/setuptools/lib: pyproject's package-dir),
    the compiled extensions included, in a directory of their own."""
    site = tmp_path_factory.mktemp("site")
    skip = shutil.ignore_patterns("__pycache__", ".ffi-built", "csrc", "build_csrc.py")
    shutil.copytree(ROOT / "harness" / "ogk", site / "ogk", ignore=skip)
    shutil.copytree(ROOT / "host" / "ogk_host", site / "ogk_host", ignore=skip)
    shutil.copytree(ROOT / "bindings" / "ogk_bindings", site / "ogk_bindings", ignore=skip)
    shutil.copytree(ROOT / "scenarios", site / "ogk_host" / "scenarios")
    return site


def in_site(site: Path, cwd: Path, code: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(site)}   # before the editable install's finder
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=120)


def test_scenarios_resolve_from_package_data(site: Path, tmp_path: Path) -> None:
    out = in_site(site, tmp_path, """
        from pathlib import Path
        import ogk_host
        from ogk_host import paths, scenario_file
        from ogk_host.binary import scenario as binary
        from ogk_host.low_thrust_transfer import products, scenario as ltt
        from ogk_host.orbit_injection import scenario as oi
        from ogk_host.rendezvous import scenario as rv
        from ogk_host import cpd_design
        shipped = Path(ogk_host.__file__).parent / "scenarios"
        assert paths.SOURCE_TREE is None and paths.SCENARIO_DIR == shipped, paths.SCENARIO_DIR
        for name in ("leo-geo", "leo_geo", "apophis", "scout_upper_stage", "moshup", "proximity_approach",
                     "rendezvous_nep_min_time"):
            got = scenario_file.resolve_scenario(name)
            assert got.parent == shipped and got.is_file(), (name, got)
        for default in (oi.DEFAULT_SCENARIO_PATH, ltt.DEFAULT_SCENARIO_PATH, rv.DEFAULT_SCENARIO_PATH,
                        binary.DEFAULT_SCENARIO_PATH, cpd_design.LEO_GEO_SCENARIO):
            assert default.parent == shipped and default.is_file(), default
        table = scenario_file.table_dir_for(scenario_file.resolve_scenario("leo-geo"))
        assert table.parent == Path.cwd() / "build" / "tables", table
        # the MPSP cache's scenario ("scenarios/apophis_cubesat.toml") is the shipped one
        import json
        doc = json.loads(products.shipped_cache().read_text())
        assert products.physics_sha256(shipped / Path(doc["scenario"]).name) == doc["physics_sha256"]
        print("ok")
        """)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


@pytest.mark.parametrize("argv, line", [
    (["mc", "leo-geo", "--runs", "1", "--target", "m7", "--json", "F.json"],
     "ogk mc: --target: the flight program of --target m7 needs the ogk repository (git clone, then make; "
     "docs/guides/install.md), not an installed wheel"),
    (["soak", "--runs", "1"],
     "ogk soak: the default soak plan (soak.toml; or give PLAN) needs the ogk repository (git clone, then "
     "make; docs/guides/install.md), not an installed wheel")])
def test_what_needs_the_repository_says_so(site: Path, tmp_path: Path, argv: list[str], line: str) -> None:
    out = in_site(site, tmp_path, f"""
        import sys
        from ogk.cli import main
        sys.exit(main({argv!r}))
        """)
    lines = out.stderr.strip().splitlines()
    assert out.returncode == 2 and lines == [line], out.stderr
    assert not (tmp_path / "build").exists()


def test_version_is_the_kernels() -> None:
    import ogk
    from ogk_bindings import kernel
    assert ogk.__version__ == kernel.version()
    from ogk.cli import build_parser
    with pytest.raises(SystemExit) as done:
        build_parser().parse_args(["--version"])
    assert done.value.code == 0
