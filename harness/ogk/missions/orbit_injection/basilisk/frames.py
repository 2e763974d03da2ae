"""ogk's orbit-injection coordinates <-> Basilisk's inertial Cartesian frame N (numpy only).

ogk (Pontani & Celani 2021, sec. 2, truth.py): position (r, xi, phi) (radius, right ascension,
declination) and velocity (v_r, v_t, v_n) in the local (r, t, n) axes, in the inertial frame
c = (c1, c2, c3): c1 towards xi = phi = 0, c3 the polar axis. Basilisk's N is taken to be c, so
r_N = r (cos phi cos xi, cos phi sin xi, sin phi) and v_N = C_c,rtn (v_r, v_t, v_n), with
C_c,rtn = R3(-xi) R2(phi) (the rtn-to-c part of N = R_A R3(-xi) R2(phi), sec. 5.4).

Attitude: ogk's C_ba (body from a, a = R_A c, eq. 9) -> Basilisk's [BN] = C_ba R_A; body rates
(P, Q, R) are omega_BN_B. Basilisk's MRP sigma_BN <-> [BN] by the usual formulas (Schaub &
Junkins, eqs. 3.152-3.153), written out here so that nothing of ogk's truth model is reused.
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

F64 = NDArray[np.float64]

#: R_A of sec. 2.2 (a components = R_A c components)
R_A = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]])


def c_from_rtn(xi: float, phi: float) -> F64:
    """C_c,rtn: c components = C @ (r, t, n) components; columns are r^, t^, n^ in c:
    r^ = (cos phi cos xi, cos phi sin xi, sin phi), t^ = (-sin xi, cos xi, 0), n^ = r^ x t^."""
    cx, sx, cp, sp = math.cos(xi), math.sin(xi), math.cos(phi), math.sin(phi)
    return np.array([[cp * cx, -sx, -sp * cx], [cp * sx, cx, -sp * sx], [sp, 0.0, cp]])


def cartesian_from_ogk(nav: F64) -> tuple[F64, F64]:
    """(r_N, v_N) [m, m/s] of nav = [r, xi, phi, v_r, v_t, v_n]."""
    c = c_from_rtn(float(nav[1]), float(nav[2]))
    return float(nav[0]) * c[:, 0], c @ np.asarray(nav[3:6], dtype=np.float64)


def ogk_from_cartesian(r_n: F64, v_n: F64) -> F64:
    """[r, xi, phi, v_r, v_t, v_n] of (r_N, v_N) (xi in (-pi, pi])."""
    x, y, z = (float(v) for v in r_n)
    r = math.sqrt(x * x + y * y + z * z)
    xi = math.atan2(y, x)
    phi = math.asin(z / r)
    c = c_from_rtn(xi, phi)
    vx, vy, vz = (float(v) for v in v_n)
    return np.array([r, xi, phi, c[0, 0] * vx + c[1, 0] * vy + c[2, 0] * vz,
                     c[0, 1] * vx + c[1, 1] * vy, c[0, 2] * vx + c[1, 2] * vy + c[2, 2] * vz])


def dcm_from_mrp(sigma: F64) -> F64:
    """[BN] of the MRP sigma_BN (Schaub & Junkins eq. 3.153, written out: called every tick)."""
    s1, s2, s3 = (float(v) for v in sigma)
    q = s1 * s1 + s2 * s2 + s3 * s3
    a, d = 1.0 - q, 1.0 / (1.0 + q) ** 2
    return d * np.array([
        [4.0 * (s1 * s1 - s2 * s2 - s3 * s3) + a * a, 8.0 * s1 * s2 + 4.0 * s3 * a,
         8.0 * s1 * s3 - 4.0 * s2 * a],
        [8.0 * s2 * s1 - 4.0 * s3 * a, 4.0 * (-s1 * s1 + s2 * s2 - s3 * s3) + a * a,
         8.0 * s2 * s3 + 4.0 * s1 * a],
        [8.0 * s3 * s1 + 4.0 * s2 * a, 8.0 * s3 * s2 - 4.0 * s1 * a,
         4.0 * (-s1 * s1 - s2 * s2 + s3 * s3) + a * a]])


def mrp_from_dcm(c: F64) -> list[float]:
    """sigma (|sigma| <= 1) of a DCM c (c[i][j]), through the quaternion (Shepperd's choice of
    the largest component keeps it well conditioned)."""
    tr = c[0][0] + c[1][1] + c[2][2]
    cand = [tr, c[0][0], c[1][1], c[2][2]]
    i = cand.index(max(cand))
    if i == 0:
        b0 = 0.5 * math.sqrt(1.0 + tr)
        b = [(c[1][2] - c[2][1]) / (4.0 * b0), (c[2][0] - c[0][2]) / (4.0 * b0),
             (c[0][1] - c[1][0]) / (4.0 * b0)]
    else:
        i -= 1
        j, k = (i + 1) % 3, (i + 2) % 3
        bi = 0.5 * math.sqrt(1.0 + 2.0 * c[i][i] - tr)
        b0 = (c[j][k] - c[k][j]) / (4.0 * bi)
        b = [0.0, 0.0, 0.0]
        b[i] = bi
        b[j] = (c[i][j] + c[j][i]) / (4.0 * bi)
        b[k] = (c[i][k] + c[k][i]) / (4.0 * bi)
    if b0 < 0.0:
        b0, b = -b0, [-v for v in b]
    return [float(v) / (1.0 + b0) for v in b]


def euler_321(c_ba: F64) -> tuple[float, float, float]:
    """(Psi, Theta, Phi) of C_ba = R1(Phi) R2(Theta) R3(Psi) (eq. 9)."""
    return (math.atan2(c_ba[0][1], c_ba[0][0]), -math.asin(min(1.0, max(-1.0, c_ba[0][2]))),
            math.atan2(c_ba[1][2], c_ba[2][2]))


def dcm_321(psi: float, theta: float, roll: float) -> list[list[float]]:
    """C_ba = R1(Phi) R2(Theta) R3(Psi) (eq. 9), frame rotations, multiplied out."""
    cps, sps, ct, st, cr, sr = (math.cos(psi), math.sin(psi), math.cos(theta), math.sin(theta),
                                math.cos(roll), math.sin(roll))
    return [[ct * cps, ct * sps, -st],
            [sr * st * cps - cr * sps, sr * st * sps + cr * cps, sr * ct],
            [cr * st * cps + sr * sps, cr * st * sps - sr * cps, cr * ct]]


def ogk_attitude(sigma_bn: F64, omega_bn_b: F64) -> F64:
    """ogk's attitude [Psi, Theta, Phi, P, Q, R] of Basilisk's (sigma_BN, omega_BN_B):
    C_ba = [BN] R_A^T, i.e. columns ([BN]_1, -[BN]_2, -[BN]_0)."""
    c = dcm_from_mrp(sigma_bn)
    c_ba = [[c[i][1], -c[i][2], -c[i][0]] for i in range(3)]
    return np.array([*euler_321(c_ba), *(float(v) for v in omega_bn_b)])


def sigma_bn_of(c_ba: F64) -> list[float]:
    """Basilisk's sigma_BN of ogk's C_ba: [BN] = C_ba R_A, columns (-C_ba,2, C_ba,0, -C_ba,1)."""
    c_bn = [[-c_ba[i][2], c_ba[i][0], -c_ba[i][1]] for i in range(3)]
    return mrp_from_dcm(c_bn)
