"""Kernel bindings: the cffi extension built from kernel/include/ogk/*.h and thin typed wrappers.

The lowest layer: imports nothing else of ogk or ogk_host (docs/design/architecture.md)."""
