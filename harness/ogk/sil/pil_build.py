"""A scenario's PIL flight program, built on demand (docs/pil.md): the family writes the generated C
(table image, flight configuration) into DIR/c, then `make pil-program PIL_PROGRAM=NAME PIL_OUT=DIR`
compiles and links it with the flight flags; the campaign flies DIR/NAME-<sha16>.elf, a copy named by
its content. For SPARC V8 (`target="sparc"`), `make pil-program-sparc` builds the same program from
the same DIR/c into DIR/sparc (the flown copy DIR/sparc/NAME-<sha16>.elf). DIR is keyed by the family (e.g. by the SHA-256 of the
tables flown), so two campaigns of one scenario share one build; a lock file serialises them."""
from __future__ import annotations

import fcntl
import hashlib
import os
import shutil
import subprocess
from collections.abc import Callable
from pathlib import Path

from ogk_bindings.errors import OgkInputError

ROOT = Path(__file__).resolve().parents[3]      #: the repository (its Makefile builds the ELF)
PIL_BUILD = ROOT / "build" / "pil"


#: target -> (make goal, where the ELF lands under DIR)
MAKE_GOAL = {"m7": ("pil-program", "."), "sparc": ("pil-program-sparc", "sparc")}


def build_program(program: str, out: Path, generate: Callable[[Path], None],
                  target: str = "m7") -> Path:
    """DIR/PROGRAM.elf for `out` = DIR (DIR/sparc/PROGRAM.elf for SPARC V8): `generate(DIR / "c")`
    once (a stamp marks it done), then make (which rebuilds what changed, e.g. the kernel). Raises
    OgkInputError with make's last lines."""
    if target not in MAKE_GOAL:
        raise OgkInputError(f"no flight program build for target {target!r}", key="--target")
    goal, sub = MAKE_GOAL[target]
    out.mkdir(parents=True, exist_ok=True)
    with open(out / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        stamp = out / "c" / ".generated"
        if not stamp.exists():
            (out / "c").mkdir(exist_ok=True)
            generate(out / "c")
            stamp.touch()
        proc = subprocess.run(["make", "-s", "-C", str(ROOT), goal,
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


def file_sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()
