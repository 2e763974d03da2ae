"""Factories of the bindings' C test models (bindings/csrc/models.h) for ogk_bindings.kernel.rk4_*.

Each factory allocates the model's parameter struct with ffi.new and returns a
CModel holding it, so the struct lives as long as the CModel."""
from __future__ import annotations

import math
from dataclasses import dataclass

from ogk_bindings._ffi import ffi, lib
from ogk_bindings.kernel import CModel


def two_body(mu: float) -> CModel:
    """x = [r(3), v(3)], xdot = [v, -mu r/|r|^3]."""
    user = ffi.new("ogk_model_two_body_t *")
    user.mu = mu
    return CModel(name="two_body", n=6, rhs=ffi.addressof(lib, "ogk_model_two_body_rhs"),
                  user=user)


def min_fuel_double_integrator(u_max: float) -> CModel:
    """x = [r, v, lambda_r, lambda_v]; mode 1 thrust on, 0 coast; S = |lambda_v| - 1."""
    user = ffi.new("ogk_model_min_fuel_di_t *")
    user.u_max = u_max
    return CModel(name="min_fuel_double_integrator", n=int(lib.OGK_MODEL_MIN_FUEL_DI_N),
                  rhs=ffi.addressof(lib, "ogk_model_min_fuel_di_rhs"), user=user,
                  switch=ffi.addressof(lib, "ogk_model_min_fuel_di_switch"))


def decay(rate: float, t_fail: float = math.inf) -> CModel:
    """x' = -rate x; the rhs fails (status OGK_E_RANGE) for t > t_fail."""
    user = ffi.new("ogk_model_decay_t *")
    user.rate = rate
    user.t_fail = t_fail
    return CModel(name="decay", n=1, rhs=ffi.addressof(lib, "ogk_model_decay_rhs"), user=user)


def oscillator(omega: float) -> CModel:
    """x = [q, q'], q'' = -omega^2 q, switching function S = q (mode ignored by the rhs)."""
    user = ffi.new("ogk_model_oscillator_t *")
    user.omega = omega
    return CModel(name="oscillator", n=2, rhs=ffi.addressof(lib, "ogk_model_oscillator_rhs"),
                  user=user, switch=ffi.addressof(lib, "ogk_model_oscillator_switch"))


@dataclass(frozen=True)
class RestToRest:
    """Closed-form minimum-fuel rest-to-rest transfer of r'' = u, |u| <= u_max:
    distance D in time T, bang-off-bang (+u_max, 0, -u_max)."""

    distance: float
    duration: float
    u_max: float

    def __post_init__(self) -> None:
        if not (self.distance > 0 and self.u_max > 0
                and self.duration ** 2 > 4 * self.distance / self.u_max):
            raise ValueError("need D > 0, u_max > 0 and T^2 > 4 D / u_max (else infeasible "
                             "or bang-bang)")

    @property
    def t_on_end(self) -> float:
        """End of the first burn, t1 = (T - sqrt(T^2 - 4 D/u_max)) / 2."""
        T = self.duration
        return (T - math.sqrt(T * T - 4.0 * self.distance / self.u_max)) / 2.0

    @property
    def switch_times(self) -> tuple[float, float]:
        t1 = self.t_on_end
        return (t1, self.duration - t1)

    @property
    def lambda_r(self) -> float:
        return -2.0 / (self.duration - 2.0 * self.t_on_end)

    def initial_state(self) -> list[float]:
        """[r, v, lambda_r, lambda_v] at t = 0 (lambda_v(0) = -T / (T - 2 t1))."""
        T = self.duration
        return [0.0, 0.0, self.lambda_r, -T / (T - 2.0 * self.t_on_end)]

    def state(self, t: float) -> list[float]:
        """Exact [r, v, lambda_r, lambda_v] at 0 <= t <= T."""
        t1, t2 = self.switch_times
        u, T = self.u_max, self.duration
        lam_v = self.initial_state()[3] - self.lambda_r * t
        v_coast = u * t1
        if t <= t1:
            r, v = 0.5 * u * t * t, u * t
        elif t <= t2:
            r, v = 0.5 * u * t1 * t1 + v_coast * (t - t1), v_coast
        else:
            tr = T - t  # symmetric deceleration: mirror of the first burn
            r, v = self.distance - 0.5 * u * tr * tr, u * tr
        return [r, v, self.lambda_r, lam_v]
