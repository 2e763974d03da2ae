"""ogk in Basilisk (docs/guides/basilisk.md): the orbit-injection flight software as Basilisk modules
(modules.py), a Basilisk simulation of the burn as an independent truth model (injection.py) and
its cross-check against ogk's own 6-DOF truth model (crosscheck.py). Needs the `bsk` package."""
