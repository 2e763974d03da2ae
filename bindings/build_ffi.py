"""Builds the cffi extension ``ogk_bindings._ogk_cffi`` (API mode) in place.

The extension compiles every kernel source (kernel/src/*.c) together with the
test models of the bindings (bindings/csrc/*.c), so Python calls exactly the C the
flight build compiles. The mission families' C helpers (batched calls of the kernel's
step functions over many runs, harness/ogk/missions/<family>/csrc/) are not built
here: the family layer builds them (harness/ogk/missions/build_csrc.py) into
extensions of their own that include this one's types (cffi's ffi.include) and
reuse the functions below (`declarations`, `macros`, `include_source`,
`kernel_sources`), so the bottom layer builds nothing of the top one.

The cdefs are generated from the headers themselves at build time; nothing of
a kernel type is restated here:

* types, enums and prototypes: ``gcc -E`` over every public header
  (kernel/include/ogk/*.h, the csrc/*.h above) and every test header
  (``TEST_HEADERS``: kernel/include/ogk/internal/*.h, the laws' test entry
  points that left the public headers, e.g. ``ogk_nmpc_interval``; declared
  here so that the bindings' cross-checks keep calling them), keeping only the lines the
  linemarkers attribute to those headers (what <stdint.h> and <stddef.h>
  declare, cffi already knows). Comments vanish, macros are expanded (array
  sizes become the constants the C compiler sees, so a -D override of a
  capacity limit cannot desynchronise Python and C), and the ``extern "C"``
  guards vanish with ``__cplusplus`` undefined. Structs are declared in full,
  so cffi checks every field offset and the size against the C compiler.
* macros: ``gcc -dM -E`` over the same headers; every ``OGK_*`` object-like
  macro defined in one of them becomes ``#define NAME ...`` (integers: cffi
  reads the value from the compiler), ``static const double NAME;`` (floating
  constants, also through <float.h> and <math.h>: OGK_REAL_MAX is DBL_MAX) or
  ``static const char *const NAME;`` (string literals). Include guards (empty
  macros) and function-like macros (ogk/real.h's OGK_R, OGK_SQRT, ...) are skipped.
  ogk/real.h's ``typedef double ogk_real_t;`` reaches the cdef as written: the
  default build's real type. The same bindings are built a second time with
  OGK_REAL_SINGLE=1 (``PRECISIONS``): ``ogk_bindings._ogk_cffi_single``, whose
  cdef says ``typedef float ogk_real_t;``; a process loads one of the two
  (ogk_bindings._ffi, env OGK_PRECISION), the wrappers keep float64 and
  convert at the kernel boundary (ogk_bindings._real).

tests/python/test_bindings.py checks independently that every function,
struct field and integer macro of the headers is reachable.

Run from anywhere:  .venv/bin/python bindings/build_ffi.py [--precision double|single|both]
(both by default; `make ffi` does this whenever a kernel source, a csrc/ file or this file changes.) setup.py builds
the same extension (`setuptools_builder`) through cffi's setuptools integration, for `pip install`
and `python -m build` (docs/guides/install.md).
"""
from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import cffi

BINDINGS_DIR = Path(__file__).resolve().parent
ROOT = BINDINGS_DIR.parent
KERNEL_INCLUDE = ROOT / "kernel" / "include"
KERNEL_SRC = ROOT / "kernel" / "src"
#: C beside the kernel: the bindings' test models
CSRC_DIRS = [BINDINGS_DIR / "csrc"]
PACKAGE_DIR = BINDINGS_DIR / "ogk_bindings"
BUILD_DIR = ROOT / "build" / "ffi"
MODULE_NAME = "ogk_bindings._ogk_cffi"
CC = os.environ.get("CC", "gcc")
# Extra -D/-U options (e.g. a capacity override) applied both to the header scan
# and to the compilation of the extension.
DEFINES = shlex.split(os.environ.get("OGK_FFI_DEFINES", ""))

#: The kernel's two real types (ogk/real.h), one extension each: "double" (the default,
#: ogk_bindings._ogk_cffi) and "single" (-DOGK_REAL_SINGLE=1, ogk_bindings._ogk_cffi_single, whose
#: cdef's ogk_real_t is float). A process loads one of them (ogk_bindings._ffi, env OGK_PRECISION).
PRECISIONS = ("double", "single")
#: the module-name suffix of each precision (the families' extensions take the same one)
PRECISION_SUFFIX = {"double": "", "single": "_single"}


def precision_defines(precision: str = "double") -> list[str]:
    """The -D options of a precision, after OGK_FFI_DEFINES (header scan and compilation alike)."""
    if precision not in PRECISIONS:
        raise ValueError(f"precision {precision!r}: expected one of {PRECISIONS}")
    return ["-DOGK_REAL_SINGLE=1"] if precision == "single" else []


def module_name(precision: str = "double") -> str:
    precision_defines(precision)  # validates
    return MODULE_NAME + PRECISION_SUFFIX[precision]


def build_dir(precision: str = "double") -> Path:
    """cffi's build directory of a precision (apart: the same sources compile to different objects)."""
    return BUILD_DIR if precision == "double" else BUILD_DIR.parent / f"ffi-{precision}"
INCLUDE_DIRS = [str(KERNEL_INCLUDE), *(str(d) for d in CSRC_DIRS)]


def public_headers() -> list[Path]:
    """Every header of the API: the kernel's public API, then the C beside it."""
    return sorted((KERNEL_INCLUDE / "ogk").glob("*.h")) + [h for d in CSRC_DIRS for h in sorted(d.glob("*.h"))]


#: The kernel's test headers (kernel/include/ogk/internal/*.h): entry points that exist for the
#: tests (ogk_nmpc_interval, ogk_mpsp_step_jacobian, ogk_blt_jacobian, ...), kept out of the public
#: headers a flight application includes, but declared to cffi like them. A separate list, so
#: that what is flight API and what is a test hook stays visible here and in test_bindings.py.
TEST_HEADERS: list[Path] = sorted((KERNEL_INCLUDE / "ogk" / "internal").glob("*.h"))


def bound_headers() -> list[Path]:
    """Every header the bindings declare: the public ones, then the test headers."""
    return public_headers() + TEST_HEADERS


def include_source(headers: list[Path]) -> str:
    """A translation unit including every header (as the kernel's users spell it)."""
    lines = []
    for h in headers:
        if h.parent == KERNEL_INCLUDE / "ogk":
            rel = f"ogk/{h.name}"
        elif h.parent == KERNEL_INCLUDE / "ogk" / "internal":
            rel = f"ogk/internal/{h.name}"
        else:
            rel = h.name
        lines.append(f'#include "{rel}"\n')
    return "".join(lines)


def _preprocess(source: str, *flags: str, include_dirs: list[str] | None = None,
                precision: str = "double") -> str:
    dirs = INCLUDE_DIRS if include_dirs is None else include_dirs
    cmd = [CC, "-std=c99", "-E", *flags, *DEFINES, *precision_defines(precision), *(f"-I{d}" for d in dirs),
           "-"]
    return subprocess.run(cmd, input=source, capture_output=True, text=True,
                          check=True).stdout


_LINEMARKER = re.compile(r'^#\s*(\d+)\s+"([^"]*)"')


def declarations(headers: list[Path], include_dirs: list[str] | None = None,
                 precision: str = "double") -> str:
    """Types, enums and prototypes of `headers`, macro-expanded, nothing else."""
    ours = {str(h.resolve()) for h in headers}
    keep = False
    out: list[str] = []
    for line in _preprocess(include_source(headers), include_dirs=include_dirs,
                            precision=precision).splitlines():
        m = _LINEMARKER.match(line)
        if m:
            path = m.group(2)
            keep = path.startswith("/") and str(Path(path).resolve()) in ours or \
                (not path.startswith("<") and str((ROOT / path).resolve()) in ours)
            continue
        if keep and line.strip():
            out.append(line)
    text = "\n".join(out) + "\n"
    # What cffi's parser does not take (none of it is in the headers today).
    text = re.sub(r"__attribute__\s*\(\(.*?\)\)", "", text)
    text = re.sub(r"\b__restrict__\b|\b__restrict\b|\brestrict\b", "", text)
    return text


_MACRO = re.compile(r"^#define\s+(OGK_\w+)(?:\s+(.*))?$")
_ANY_MACRO = re.compile(r"^#define\s+(\w+)(?:\s+(.*))?$")
# <math.h>'s HUGE_VAL (OGK_REAL_HUGE_VAL) is a builtin call, not a literal
_FLOAT_BUILTIN = re.compile(r"\b__builtin_(?:huge_val|inf|nan)f?\b")
_FLOAT = re.compile(r"(?<![\w.])(\d+\.\d*|\.\d+|\d+[eE][-+]?\d+)(?:[eE][-+]?\d+)?[fFlL]?(?![\w.])")


def macros(headers: list[Path], include_dirs: list[str] | None = None, precision: str = "double"
           ) -> list[tuple[str, str, str]]:
    """(name, kind, value) of the object-like OGK_* macros of `headers` (and of what they
    include), kind in {"int", "double", "string"}; empty (include-guard) macros skipped."""
    text = _preprocess(include_source(headers), "-dM", include_dirs=include_dirs, precision=precision)
    values: dict[str, str] = {}
    # every object-like macro the headers see (<float.h>'s, <math.h>'s, the compiler's), to expand
    # the OGK_* ones through them: ogk/real.h's OGK_REAL_EPSILON is DBL_EPSILON, __DBL_EPSILON__,
    # a floating literal
    every: dict[str, str] = {}
    for line in text.splitlines():
        m = _ANY_MACRO.match(line)
        if m and m.group(2) is not None and m.group(2).strip():
            every[m.group(1)] = m.group(2).strip()
        m = _MACRO.match(line)
        if m and m.group(2) is not None and m.group(2).strip():
            values[m.group(1)] = m.group(2).strip()

    def expanded(value: str) -> str:
        # Other macros replaced by their values (a macro may alias another, e.g.
        # OGK_CPD_ANGLE_LIMIT -> OGK_ANGLE_LIMIT, OGK_REAL_MAX -> DBL_MAX), so the kind is the compiler's.
        for _ in range(16):
            new = re.sub(r"\b[A-Za-z_]\w*\b", lambda m: f"({every[m.group(0)]})" if m.group(0) in every
                         else m.group(0), value)
            if new == value:
                break
            value = new
        return value

    found: list[tuple[str, str, str]] = []
    for name, value in values.items():
        full = expanded(value)
        if full.lstrip("( ").startswith('"'):
            kind = "string"
        elif _FLOAT.search(full) or _FLOAT_BUILTIN.search(full):
            kind = "double"
        else:
            kind = "int"
        found.append((name, kind, value))
    return sorted(found)


def macro_cdefs(found: list[tuple[str, str, str]]) -> str:
    lines = []
    for name, kind, _value in found:
        if kind == "int":
            lines.append(f"#define {name} ...")
        elif kind == "double":
            lines.append(f"static const double {name};")
        else:
            lines.append(f"static const char *const {name};")
    return "\n".join(lines) + "\n"


def generated_cdef(precision: str = "double") -> str:
    headers = bound_headers()
    return declarations(headers, precision=precision) + macro_cdefs(macros(headers, precision=precision))


def source_paths(paths: list[Path], relative: bool = False) -> list[str]:
    """`paths` as the compiler is given them: absolute (`make ffi`: cffi compiles in its build
    directory), or relative to the repository (setup.py: setuptools takes no absolute source path,
    and runs there)."""
    return [p.relative_to(ROOT).as_posix() if relative else str(p) for p in paths]


def kernel_sources(relative: bool = False) -> list[str]:
    """The kernel's sources (every extension that calls the kernel compiles them, same flags)."""
    return source_paths(sorted(KERNEL_SRC.rglob("*.c")), relative)


def bound_sources(relative: bool = False) -> list[str]:
    """What this extension compiles: the kernel, then the bindings' test models."""
    return kernel_sources(relative) + source_paths([p for d in CSRC_DIRS for p in sorted(d.glob("*.c"))],
                                                   relative)


#: the compiler options of every extension over the kernel (-I kernel/src: the internal headers the
#: kernel's modules share, kernel/src/*.h; docs/design/architecture.md, "Kernel source layout")
COMPILE_ARGS = ["-std=c99", "-O2", f"-I{KERNEL_SRC}", *DEFINES]


#: cffi's glue is written to the stable ABI (_cffi_include.h defines Py_LIMITED_API); said here too, so
#: that `make ffi` and setup.py (where cffi sets it) name the extension alike: _ogk_cffi.abi3.so
PY_LIMITED_API = True


def compile_args(precision: str = "double") -> list[str]:
    """COMPILE_ARGS with the precision's define (the double build's are COMPILE_ARGS as they were)."""
    return [*COMPILE_ARGS, *precision_defines(precision)]


def make_builder(relative: bool = False, precision: str = "double") -> cffi.FFI:
    headers = bound_headers()
    cdef = generated_cdef(precision)
    tmp = build_dir(precision)
    tmp.mkdir(parents=True, exist_ok=True)
    (tmp / "generated_cdef.h").write_text(cdef)  # for inspection only
    ffibuilder = cffi.FFI()
    ffibuilder.cdef(cdef)
    ffibuilder.set_source(
        module_name(precision),
        include_source(headers),
        sources=bound_sources(relative),
        include_dirs=INCLUDE_DIRS,
        extra_compile_args=compile_args(precision),
        libraries=["m"],
        py_limited_api=PY_LIMITED_API,
    )
    return ffibuilder


def setuptools_builder() -> cffi.FFI:
    """The same extension for cffi's setuptools integration (setup.py's cffi_modules: `pip install .`,
    `python -m build`, the Makefile's editable install), its sources relative to the repository."""
    return make_builder(relative=True)


def setuptools_builder_single() -> cffi.FFI:
    """The single-precision extension (ogk_bindings._ogk_cffi_single) for setup.py, likewise."""
    return make_builder(relative=True, precision="single")


def main(argv: list[str] | None = None) -> int:
    import argparse
    parser = argparse.ArgumentParser(description="builds the kernel's cffi extension of each precision")
    parser.add_argument("--precision", choices=[*PRECISIONS, "both"], default="both")
    args = parser.parse_args(argv)
    for precision in PRECISIONS if args.precision == "both" else (args.precision,):
        tmp = build_dir(precision)
        tmp.mkdir(parents=True, exist_ok=True)
        built = Path(make_builder(precision=precision).compile(tmpdir=str(tmp), verbose=False))
        # Install the extension next to the package sources (editable install).
        stem = module_name(precision).rsplit(".", 1)[1]
        for old in PACKAGE_DIR.glob(f"{stem}.*"):
            old.unlink()
        target = PACKAGE_DIR / built.name
        shutil.copy2(built, target)
        print(f"build_ffi: {target.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
