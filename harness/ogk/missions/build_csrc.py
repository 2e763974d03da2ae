"""Builds each mission family's C helpers (harness/ogk/missions/<family>/csrc/*.c: batched calls of
the kernel's step functions over many runs) into the family's own cffi extension,
``ogk.missions.<family>._csrc_cffi`` (API mode), in place.

The family layer builds its C; the bindings build the kernel's (bindings/build_ffi.py, whose
header scan this reuses). A family's extension:
* includes the bindings' FFI (cffi's ``ffi.include``): the kernel's types are the bindings' own, so
  a context made by ``ogk_bindings._ffi.ffi`` is passed to a batch loop as it is, and the batch
  module imports ``ogk_bindings._ogk_cffi`` at run time;
* declares only what the family's csrc/*.h declare (their prototypes, and the OGK_* macros they
  define beyond the kernel's), generated from the headers as the bindings' are;
* compiles the kernel's sources with the family's, with the bindings' compiler options, so that the
  batch loops call the same kernel code (a copy of it in this extension; the kernel keeps no state
  outside the contexts it is given).

Run from anywhere:  .venv/bin/python harness/ogk/missions/build_csrc.py
(`make ffi` runs it after bindings/build_ffi.py.) setup.py builds the same extensions through cffi's
setuptools integration (`cffi_modules`: `cffi_module_specs`, one `family_<name>` builder per family
below), for `pip install` and `python -m build`. Not imported at run time, and not in the wheel.
"""
from __future__ import annotations

import functools
import shutil
import sys
from pathlib import Path

import cffi

MISSIONS_DIR = Path(__file__).resolve().parent
ROOT = MISSIONS_DIR.parents[2]
sys.path.insert(0, str(ROOT / "bindings"))
import build_ffi as kernel_ffi  # noqa: E402  (the bindings' build script, not a package)

BUILD_DIR = ROOT / "build" / "ffi-families"


def families_with_csrc() -> list[Path]:
    """The csrc/ directory of every family that has C helpers."""
    return sorted(d for d in MISSIONS_DIR.glob("*/csrc") if any(d.glob("*.c")))


def module_name(csrc: Path, precision: str = "double") -> str:
    """``ogk.missions.<family>._csrc_cffi``, with the precision's suffix (build_ffi.PRECISION_SUFFIX):
    ``_csrc_cffi_single`` includes the kernel's float extension, ``_ogk_cffi_single``."""
    kernel_ffi.precision_defines(precision)  # validates
    return f"ogk.missions.{csrc.parent.name}._csrc_cffi{kernel_ffi.PRECISION_SUFFIX[precision]}"


def family_builder(csrc: Path, kernel: cffi.FFI, relative: bool = False,
                   precision: str = "double") -> cffi.FFI:
    """The FFI of one family's C helpers, on the kernel's FFI `kernel` of the same `precision`
    (`relative`: the sources relative to the repository, for setup.py; build_ffi.source_paths)."""
    headers = sorted(csrc.glob("*.h"))
    include_dirs = [*kernel_ffi.INCLUDE_DIRS, str(csrc)]
    kernel_macros = {name for name, _, _ in kernel_ffi.macros(kernel_ffi.bound_headers(), precision=precision)}
    own = [m for m in kernel_ffi.macros(headers, include_dirs, precision=precision) if m[0] not in kernel_macros]
    builder = cffi.FFI()
    builder.include(kernel)
    builder.cdef(kernel_ffi.declarations(headers, include_dirs, precision=precision) +
                 kernel_ffi.macro_cdefs(own))
    builder.set_source(
        module_name(csrc, precision),
        # the kernel's headers first: the C of the included types
        kernel_ffi.include_source(kernel_ffi.bound_headers() + headers),
        sources=kernel_ffi.kernel_sources(relative) + kernel_ffi.source_paths(sorted(csrc.glob("*.c")),
                                                                             relative),
        include_dirs=include_dirs,
        extra_compile_args=kernel_ffi.compile_args(precision),
        libraries=["m"],
        py_limited_api=kernel_ffi.PY_LIMITED_API,
    )
    return builder


def _family_ffi(csrc: Path, precision: str = "double") -> cffi.FFI:
    return family_builder(csrc, kernel_ffi.make_builder(relative=True, precision=precision), relative=True,
                          precision=precision)


def _builder_name(csrc: Path, precision: str) -> str:
    return f"family_{csrc.parent.name}{kernel_ffi.PRECISION_SUFFIX[precision]}"


def cffi_module_specs() -> list[str]:
    """setup.py's `cffi_modules` entries: this file and the builder of each family with C helpers, of
    each precision (family_<name>, family_<name>_single)."""
    here = Path(__file__).resolve().relative_to(ROOT).as_posix()
    return [f"{here}:{_builder_name(csrc, p)}" for p in kernel_ffi.PRECISIONS for csrc in families_with_csrc()]


# one module-level builder per family and precision (cffi's setuptools integration names a builder by
# variable)
for _csrc in families_with_csrc():
    for _precision in kernel_ffi.PRECISIONS:
        globals()[_builder_name(_csrc, _precision)] = functools.partial(_family_ffi, _csrc, _precision)


def main(argv: list[str] | None = None) -> int:
    import argparse
    parser = argparse.ArgumentParser(description="builds the families' C helpers of each precision")
    parser.add_argument("--precision", choices=[*kernel_ffi.PRECISIONS, "both"], default="both")
    args = parser.parse_args(argv)
    for precision in kernel_ffi.PRECISIONS if args.precision == "both" else (args.precision,):
        kernel = kernel_ffi.make_builder(precision=precision)
        for csrc in families_with_csrc():
            tmp = BUILD_DIR / f"{csrc.parent.name}{kernel_ffi.PRECISION_SUFFIX[precision]}"
            tmp.mkdir(parents=True, exist_ok=True)
            built = Path(family_builder(csrc, kernel, precision=precision).compile(tmpdir=str(tmp),
                                                                                  verbose=False))
            stem = module_name(csrc, precision).rsplit(".", 1)[1]
            for old in csrc.parent.glob(f"{stem}.*"):
                old.unlink()
            target = csrc.parent / built.name
            shutil.copy2(built, target)
            print(f"build_csrc: {target.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
