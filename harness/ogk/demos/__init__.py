"""Demonstrations of the kernel through the bindings (`ogk demo NAME`): small end-to-end runs that
are neither a mission family nor the campaign engine. They import the bindings only."""
