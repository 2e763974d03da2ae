"""What pyproject.toml cannot say: the version, read from the kernel's header, and the compiled part.

* The version is `OGK_VERSION_MAJOR.MINOR.PATCH` of kernel/include/ogk/version.h (the one place:
  CHANGELOG.md, "Versioning"); pyproject.toml declares it dynamic.
* The cffi extensions (cffi's setuptools integration, `cffi_modules`) are described by the scripts
  `make ffi` runs, not by a copy: the kernel's, `ogk_bindings._ogk_cffi` (bindings/build_ffi.py,
  `setuptools_builder`) and its single-precision twin `ogk_bindings._ogk_cffi_single`
  (`setuptools_builder_single`, OGK_REAL_SINGLE=1: `OGK_PRECISION=single`), then each mission family's
  C helpers, `ogk.missions.<family>._csrc_cffi` and `_csrc_cffi_single` (harness/ogk/missions/build_csrc.py,
  `family_<name>` and `family_<name>_single` builders per family with a csrc/). So
  `pip install .`, `python -m build` and the Makefile's `pip install -e .` compile the kernel with the
  same sources and options as `make ffi` (the editable install builds them in place, where `make ffi`
  puts them). docs/guides/install.md.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = Path(__file__).resolve().parent
VERSION_H = HERE / "kernel" / "include" / "ogk" / "version.h"

sys.path.insert(0, str(HERE / "harness" / "ogk" / "missions"))
import build_csrc  # noqa: E402  (the families' extensions, on bindings/build_ffi.py's header scan)


def kernel_version() -> str:
    """MAJOR.MINOR.PATCH of version.h, which must agree with its OGK_VERSION_STRING."""
    text = VERSION_H.read_text()
    parts = []
    for part in ("MAJOR", "MINOR", "PATCH"):
        m = re.search(rf"^#define OGK_VERSION_{part} +(\d+) *$", text, re.M)
        if m is None:
            raise SystemExit(f"setup.py: {VERSION_H}: no '#define OGK_VERSION_{part} <number>' line")
        parts.append(m.group(1))
    version = ".".join(parts)
    string = re.search(r'^#define OGK_VERSION_STRING "([^"]*)"', text, re.M)
    if string is None or string.group(1) != version:
        raise SystemExit(f"setup.py: {VERSION_H}: OGK_VERSION_STRING is not {version}")
    return version


class BuildPy(build_py):
    """The packages without the families' build script (build_csrc.py runs at build time only)."""

    def find_package_modules(self, package: str, package_dir: str) -> list[tuple[str, str, str]]:
        return [m for m in super().find_package_modules(package, package_dir)
                if (m[0], m[1]) != ("ogk.missions", "build_csrc")]


setup(
    version=kernel_version(),
    cffi_modules=["bindings/build_ffi.py:setuptools_builder", "bindings/build_ffi.py:setuptools_builder_single",
                  *build_csrc.cffi_module_specs()],
    cmdclass={"build_py": BuildPy},
    # setuptools' own directories apart from the Makefile's build/<target> (no parallel build_ext: the
    # two extensions compile the same kernel sources into the same objects)
    options={"build": {"build_base": "build/setuptools"}},
)
