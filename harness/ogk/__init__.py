"""ogk software-in-the-loop harness: kernel bindings, truth models, campaigns."""
from importlib.metadata import PackageNotFoundError, version

try:
    # the distribution's version, which setup.py reads from kernel/include/ogk/version.h (one place)
    __version__ = version("ogk")
except PackageNotFoundError:  # pragma: no cover - the sources on sys.path without an install
    __version__ = "0+unknown"
del PackageNotFoundError, version
