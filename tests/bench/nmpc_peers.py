"""The NMPC re-solve's peers for `make bench-nmpc`: CasADi 3.8's FATROP and IPOPT, JIT-compiled by gcc -O2.

Both solve RendezvousNlp's NLP (host/ogk_host/rendezvous/nlp.py: the same RK4 subinterval map, bounds,
terminal condition and minimum-time objective as the kernel), written in the form each solver exploits:

* IPOPT: RendezvousNlp's own layout (all node states, all node controls, T), exact Hessian.
* FATROP: the same NLP as an optimal control problem in stages, which FATROP's structure detection needs
  (variables stage by stage, every gap-closing row `z_{k+1} - f_k(z_k, v_k) = 0` in order). The subinterval
  map F(X_k, U_k, U_{k+1}, h) depends on the next node's control, so stage k's state carries its node's
  control and the horizon: z_k = (X_k, U_k, T_k), stage control v_k = U_{k+1}, dynamics
  z_{k+1} = (F(X_k, U_k, v_k, T_k / N, t0 + k T_k / N), v_k, T_k). Eliminating the copies T_k = T and the
  carried controls gives RendezvousNlp's NLP exactly: the same optimum, the same Newton steps.

The JIT: every derivative function is compiled once per machine (CasADi's shell compiler, gcc -O2) and the
solver saved with `jit_serialize = "link"` under build/bench/nmpc/peers/, named by a hash of the problem
and the options; later runs load it (no compile in the timing, none after the first run).
"""
from __future__ import annotations

import contextlib
import hashlib
import time
from dataclasses import dataclass
from pathlib import Path

import casadi as ca
import numpy as np

from ogk_host.rendezvous.nlp import RendezvousNlp
from ogk_host.rendezvous.plan import Plan

NX = 5
#: bumped when the JIT options change, so a cached solver of older options is rebuilt
JIT_FORMAT = 3


@dataclass(frozen=True)
class PeerSolve:
    plan: Plan
    iterations: int
    success: bool
    status: str
    wall_s: float      #: the solver call (CasADi Function evaluation)
    cpu_s: float       #: process CPU time around the solver call
    lam_g: np.ndarray
    lam_x: np.ndarray


def _jit_opts(cache: Path, name: str) -> dict:
    """CasADi's JIT through gcc -O2, the object and library in `cache` (an absolute path)."""
    return {"jit": True, "compiler": "shell", "jit_temp_suffix": False, "jit_name": name, "jit_cleanup": False,
            "jit_serialize": "link", "jit_options": {"flags": ["-O2"], "verbose": False, "cleanup": False,
                                                     "directory": f"{cache}/"}}


def _cached(cache: Path | None, key: str, build) -> ca.Function:
    """The solver saved under cache/<key>.casadi, built (and JIT-compiled) by `build(name)` when missing;
    cache None: built without JIT and not saved (the tests' check of the transcription)."""
    if cache is None:
        return build(key)
    cache = cache.resolve()
    cache.mkdir(parents=True, exist_ok=True)
    path = cache / f"{key}.casadi"
    if path.exists():
        try:
            return ca.Function.load(str(path))
        except RuntimeError:
            path.unlink()
    with contextlib.chdir(cache):   # CasADi writes the generated <name>.c into the working directory
        solver = build(key)
    solver.save(str(path))
    return solver


def _problem_hash(nlp: RendezvousNlp, n: int, *parts: object) -> str:
    h = hashlib.sha256(repr((JIT_FORMAT, nlp.scenario, n, nlp.rk4_steps, nlp.third_bodies, nlp.objective,
                             nlp.horizon_bounds, ca.__version__) + parts).encode())
    return h.hexdigest()[:12]


def _timed(solver: ca.Function, args: dict) -> tuple[dict, float, float]:
    cpu, wall = time.process_time(), time.perf_counter()
    sol = solver(**args)
    return sol, time.perf_counter() - wall, time.process_time() - cpu


# ------------------------------------------------------------------------------------------------ IPOPT
class IpoptJit:
    """RendezvousNlp's IPOPT solver, JIT-compiled (cache None: not compiled); `tol` / `constr_viol_tol` as the
    caller's."""

    def __init__(self, nlp: RendezvousNlp, n: int, cache: Path | None, tol: float, constr_viol_tol: float,
                 warm: bool) -> None:
        self.nlp, self.n = nlp, n
        cache = cache.resolve() if cache is not None else None
        problem, self.bounds = nlp.problem(n, "MX")
        opts = dict(nlp.ipopt)
        opts.update({"ipopt.tol": tol, "ipopt.constr_viol_tol": constr_viol_tol})
        if warm:
            opts.update({"ipopt.warm_start_init_point": "yes", "ipopt.mu_init": nlp.warm_mu_init,
                         "ipopt.warm_start_bound_push": 1e-9, "ipopt.warm_start_bound_frac": 1e-9,
                         "ipopt.warm_start_slack_bound_push": 1e-9, "ipopt.warm_start_slack_bound_frac": 1e-9,
                         "ipopt.warm_start_mult_bound_push": 1e-9})
        key = "ipopt_" + _problem_hash(nlp, n, sorted(opts.items()))
        self.solver = _cached(cache, key, lambda name: ca.nlpsol(
            name, "ipopt", problem, {**opts, **(_jit_opts(cache, name) if cache else {})}))

    def solve(self, t0: float, x0: np.ndarray, guess: Plan, lam_g: np.ndarray | None = None,
              lam_x: np.ndarray | None = None) -> PeerSolve:
        b, n, nu = self.bounds, self.n, self.nlp.nu
        w0 = np.concatenate([guess.states.ravel(), guess.controls.ravel(), [guess.horizon]])
        args = dict(x0=np.clip(w0, b["lbx"], b["ubx"]), p=np.concatenate([[t0], x0]), lbx=b["lbx"],
                    ubx=b["ubx"], lbg=b["lbg"], ubg=b["ubg"])
        if lam_g is not None:
            args.update(lam_g0=lam_g, lam_x0=lam_x)
        sol, wall, cpu = _timed(self.solver, args)
        st = self.solver.stats()
        w = np.asarray(sol["x"]).ravel()
        plan = Plan(t0=t0, horizon=float(w[-1]), states=w[: NX * (n + 1)].reshape(n + 1, NX),
                    controls=w[NX * (n + 1): (NX + nu) * (n + 1)].reshape(n + 1, nu))
        return PeerSolve(plan, int(st["iter_count"]), bool(st["success"]), str(st["return_status"]), wall, cpu,
                         np.asarray(sol["lam_g"]).ravel(), np.asarray(sol["lam_x"]).ravel())


# ------------------------------------------------------------------------------------------------ FATROP
class FatropJit:
    """The same NLP in stages (module docstring) for FATROP, JIT-compiled (cache None: not compiled)."""

    def __init__(self, nlp: RendezvousNlp, n: int, cache: Path | None, tol: float, constr_viol_tol: float,
                 extra: dict | None = None) -> None:
        if nlp.max_sweep_rad is not None or nlp.third_bodies or nlp.arrival_max is not None:
            raise ValueError("the FATROP peer covers the bench's NLP: no sweep rows, third bodies or deadline")
        self.nlp, self.n = nlp, n
        cache = cache.resolve() if cache is not None else None
        nu, m = nlp.nu, nlp.model
        nz = NX + nu + 1
        # MX: the subinterval map stays one function called N times, so the JIT compiles its derivatives
        # once (as RendezvousNlp's map does for IPOPT), not N inlined copies
        p = ca.MX.sym("p", 1 + NX)                       # (t0, x0)
        z = [ca.MX.sym(f"z{k}", nz) for k in range(n + 1)]
        v = [ca.MX.sym(f"v{k}", nu) for k in range(n)]
        w, g, lbg, ubg, eq = [], [], [], [], []
        lbz, ubz = self._stage_bounds()
        lbw, ubw = [], []
        for k in range(n + 1):
            xk, uk, tk = z[k][:NX], z[k][NX:NX + nu], z[k][NX + nu]
            w.append(z[k]); lbw.append(lbz); ubw.append(ubz)
            if k == 0:
                g.append(xk - p[1:]); eq += [True] * NX
                lbg.append(np.zeros(NX)); ubg.append(np.zeros(NX))
            if k < n:
                w.append(v[k]); lbw.append(lbz[NX:NX + nu]); ubw.append(ubz[NX:NX + nu])
                h = tk / n
                xn = nlp._interval(xk, uk, v[k], h, p[0] + k * h)   # noqa: SLF001
                g.append(z[k + 1] - ca.vertcat(xn, v[k], tk)); eq += [True] * nz
                lbg.append(np.zeros(nz)); ubg.append(np.zeros(nz))
            else:
                t_f = p[0] + tk
                mars = ca.vertcat(m.mars_radius, m.mars_theta0 + m.mars_rate * t_f, 0.0, m.mars_radius ** -0.5)
                g.append(xk[:4] - mars); eq += [True] * 4
                lbg.append(np.zeros(4)); ubg.append(np.zeros(4))
        f = z[n][NX + nu]
        problem = {"x": ca.vertcat(*w), "p": p, "f": f, "g": ca.vertcat(*g)}
        self.lbw, self.ubw = np.concatenate(lbw), np.concatenate(ubw)
        self.lbg, self.ubg = np.concatenate(lbg), np.concatenate(ubg)
        opts = {"structure_detection": "auto", "equality": eq, "expand": False, "print_time": False,
                "fatrop.print_level": 0, "fatrop.tol": tol, "fatrop.constr_viol_tol": constr_viol_tol,
                **{f"fatrop.{k}": v_ for k, v_ in (extra or {}).items()}}
        key = "fatrop_" + _problem_hash(nlp, n, sorted((k, str(v_)) for k, v_ in opts.items()))
        self.solver = _cached(cache, key, lambda name: ca.nlpsol(
            name, "fatrop", problem, {**opts, **(_jit_opts(cache, name) if cache else {})}))

    def _stage_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """RendezvousNlp's bounds on one stage state z = (X, U, T)."""
        b = self.nlp.problem(self.n)[1]
        n, nu = self.n, self.nlp.nu
        xs = slice(0, NX)
        us = slice(NX * (n + 1), NX * (n + 1) + nu)
        lo = np.concatenate([b["lbx"][xs], b["lbx"][us], b["lbx"][-1:]])
        hi = np.concatenate([b["ubx"][xs], b["ubx"][us], b["ubx"][-1:]])
        return lo, hi

    def solve(self, t0: float, x0: np.ndarray, guess: Plan, lam_g: np.ndarray | None = None,
              lam_x: np.ndarray | None = None) -> PeerSolve:
        n, nu = self.n, self.nlp.nu
        parts = []
        for k in range(n + 1):
            parts += [guess.states[k], guess.controls[k], [guess.horizon]]
            if k < n:
                parts.append(guess.controls[k + 1])
        w0 = np.clip(np.concatenate(parts), self.lbw, self.ubw)
        args = dict(x0=w0, p=np.concatenate([[t0], x0]), lbx=self.lbw, ubx=self.ubw, lbg=self.lbg,
                    ubg=self.ubg)
        if lam_g is not None:
            args.update(lam_g0=lam_g, lam_x0=lam_x)
        sol, wall, cpu = _timed(self.solver, args)
        st = self.solver.stats()
        w = np.asarray(sol["x"]).ravel()
        nz = NX + nu + 1
        stride = nz + nu
        zs = np.array([w[k * stride: k * stride + nz] for k in range(n + 1)])
        plan = Plan(t0=t0, horizon=float(zs[n, -1]), states=zs[:, :NX].copy(), controls=zs[:, NX:NX + nu].copy())
        return PeerSolve(plan, int(st["iter_count"]), bool(st["success"]), str(st["return_status"]), wall, cpu,
                         np.asarray(sol["lam_g"]).ravel(), np.asarray(sol["lam_x"]).ravel())
