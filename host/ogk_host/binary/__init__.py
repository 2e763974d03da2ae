"""Binary-asteroid BLT transfers (Xiong & Wang, Constant-Thrust Orbital Transfer about Binary Asteroids Using
Bilinear Tangent Guidance): the ground side of issue 11 -- the scenario (scenarios/moshup.toml), the units,
the model of docs/design/blt.md section 1 in numpy, libration points, Lyapunov and halo orbits, their manifolds and
the reference propagation of a BLT segment chain (docs/design/blt-ground.md)."""
from .dynamics import Model, kernel_model, model_from_scenario
from .scenario import BinaryScenario, load_scenario
from .units import Units

__all__ = ["BinaryScenario", "Model", "Units", "kernel_model", "load_scenario", "model_from_scenario"]
