"""The proximity-approach family: the kernel's ogk_prox_* NMPC flown against a two-body truth."""
