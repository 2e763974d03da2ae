"""A scenario's PIL flight program, built on demand (docs/guides/pil.md): the family writes the generated C
(table image, flight configuration) into DIR/c, then `make pil-program PIL_PROGRAM=NAME PIL_OUT=DIR`
compiles and links it with the flight flags; the campaign flies DIR/NAME-<sha16>.elf, a copy named by
its content. For SPARC V8 (`target="sparc"`), `make pil-program-sparc` builds the same program from
the same DIR/c into DIR/sparc (the flown copy DIR/sparc/NAME-<sha16>.elf). For the Cortex-M4F
(`target="m4f"`, the single-precision kernel), the C is generated for a float kernel
(ogk_host.cgen.generated_precision("single"): real literals OGK_R(...), F32 table images) into
DIR/m4f/c, and `make pil-program-m4f` builds DIR/m4f/NAME.elf. DIR is keyed by the family (e.g. by
the SHA-256 of the tables flown), so two campaigns of one scenario share one build; a lock file serialises them. The C is
generated again at every build, into DIR/gen/c, and a file replaces DIR/c's only when its content
changed (the generation stamp aside): a change of the family's settings (not only of the scenario
file that keys DIR) reaches the flight program, and an unchanged one does not make it rebuild."""
from __future__ import annotations

import fcntl
import hashlib
import os
import re
import shutil
import subprocess
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ogk_bindings.errors import OgkInputError
from ogk_host.paths import WORK_ROOT, need_repository

from .precision import TARGET_PRECISION

#: the repository (its Makefile builds the ELF); from an installed wheel, the current directory (where
#: products go; a flight program needs the repository: build_program says so in one line)
ROOT = WORK_ROOT
PIL_BUILD = ROOT / "build" / "pil"


#: target -> (make goal, where the ELF lands under DIR)
MAKE_GOAL = {"m7": ("pil-program", "."), "sparc": ("pil-program-sparc", "sparc"),
             "m4f": ("pil-program-m4f", "m4f")}
#: target -> where its generated C lives under DIR (the double targets share DIR/c)
GEN_DIR = {"m7": ".", "sparc": ".", "m4f": "m4f"}


def build_program(program: str, out: Path, generate: Callable[[Path], None],
                  target: str = "m7") -> Path:
    """DIR/PROGRAM.elf for `out` = DIR (DIR/sparc/PROGRAM.elf for SPARC V8): `generate(DIR / "c")`
    once (a stamp marks it done), then make (which rebuilds what changed, e.g. the kernel). Raises
    OgkInputError with make's last lines."""
    if target not in MAKE_GOAL:
        raise OgkInputError(f"no flight program build for target {target!r}", key="--target")
    goal, sub = MAKE_GOAL[target]
    repository = need_repository(f"the {program} flight program for --target {target}", key="--target")
    out.mkdir(parents=True, exist_ok=True)
    with open(out / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        from ogk_host.cgen import generated_precision
        with generated_precision(TARGET_PRECISION[target]):
            _generate_changed(out / GEN_DIR[target], generate)
        proc = subprocess.run(["make", "-s", "-C", str(repository), goal,
                               f"PIL_PROGRAM={program}", f"PIL_OUT={out.resolve()}"],
                              capture_output=True, text=True)
        if proc.returncode != 0:
            tail = " | ".join((proc.stdout + proc.stderr).strip().splitlines()[-4:])
            raise OgkInputError(f"the {program} flight program did not build for {target}: {tail}",
                                path=out)
        # the campaign flies a copy named by its content: a later rebuild (another campaign, a
        # changed kernel) never changes the ELF under a running campaign or its recorded SHA-256
        elf = out / sub / f"{program}.elf"
        flown = out / sub / f"{program}-{file_sha256(elf)[:16]}.elf"
        if not flown.exists():
            tmp = flown.with_suffix(".tmp")
            shutil.copyfile(elf, tmp)
            # executable: qemu-user runs the file as a program (qemu-system-arm only reads it)
            os.chmod(tmp, 0o755)
            os.replace(tmp, flown)
    return flown


def ensure_plugin(plugin: Path) -> Path:
    """The QEMU instruction-count plugin, built on demand as the flight programs are (`make
    qemu-plugin`; a tree built by `make all` has the programs' toolchain but not the plugin).
    Raises OgkInputError with make's last lines."""
    if plugin.is_file():
        return plugin
    repository = need_repository("the QEMU instruction-count plugin (make qemu-plugin)")
    PIL_BUILD.mkdir(parents=True, exist_ok=True)
    with open(PIL_BUILD / ".plugin.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not plugin.is_file():
            proc = subprocess.run(["make", "-s", "-C", str(repository), "qemu-plugin"], capture_output=True,
                                  text=True)
            if proc.returncode != 0 or not plugin.is_file():
                tail = " | ".join((proc.stdout + proc.stderr).strip().splitlines()[-4:])
                raise OgkInputError(f"the QEMU instruction-count plugin did not build (make qemu-plugin): {tail}",
                                    path=plugin)
    return plugin


#: the generation stamp of ogk_host.cgen's header comment: not content
_STAMP = re.compile(rb"^/\* Generated by (.*?) on \S+ -- do not edit\.$", re.MULTILINE)


def _generate_changed(out: Path, generate: Callable[[Path], None]) -> None:
    """generate(OUT/gen/c), then each file moved into OUT/c when it is new or its content (stamp
    aside) differs; OUT/gen removed."""
    gen = out / "gen"
    shutil.rmtree(gen, ignore_errors=True)
    (gen / "c").mkdir(parents=True)
    generate(gen / "c")
    (out / "c").mkdir(exist_ok=True)
    for new in sorted((gen / "c").iterdir()):
        old = out / "c" / new.name
        if not old.exists() or _STAMP.sub(rb"", old.read_bytes()) != _STAMP.sub(rb"", new.read_bytes()):
            os.replace(new, old)
    shutil.rmtree(gen)


def file_sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def nmpc_single_precision_tolerances(cfg: Any) -> None:
    """The NMPC configuration `cfg` (cffi ogk_nmpc_config_t *) with its tolerances floored for a
    single-precision kernel when the C is generated for one (ogk.sil.precision.NMPC_SINGLE_FLOORS); unchanged otherwise."""
    from ogk_host.cgen import current_precision

    from .precision import NMPC_SINGLE_FLOORS, nmpc_tolerances
    floored = nmpc_tolerances({k: getattr(cfg, k) for k in NMPC_SINGLE_FLOORS}, current_precision())
    for name, value in floored.items():
        setattr(cfg, name, value)
