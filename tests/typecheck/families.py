"""Checked by mypy in `make test-imports` (issue 33): every family, and the test family, is a
ogk.sil.family.MissionFamily, verb by verb with the protocol's types. Never run; an error here is a
family whose verb's signature or capability left the protocol."""
from __future__ import annotations

from point_mass_family import FAMILY as POINT_MASS

from ogk.missions.binary.family import FAMILY as BINARY_ASTEROID
from ogk.missions.low_thrust_transfer.family import FAMILY as LOW_THRUST_TRANSFER
from ogk.missions.orbit_injection.family import FAMILY as ORBIT_INJECTION
from ogk.missions.proximity.family import FAMILY as PROXIMITY_APPROACH
from ogk.missions.rendezvous.family import FAMILY as LOW_THRUST_RENDEZVOUS
from ogk.sil.family import MissionFamily

orbit_injection: MissionFamily = ORBIT_INJECTION
low_thrust_transfer: MissionFamily = LOW_THRUST_TRANSFER
low_thrust_rendezvous: MissionFamily = LOW_THRUST_RENDEZVOUS
binary_asteroid: MissionFamily = BINARY_ASTEROID
proximity_approach: MissionFamily = PROXIMITY_APPROACH
point_mass: MissionFamily = POINT_MASS
