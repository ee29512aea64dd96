#!/usr/bin/env python3
"""Reference peer for benchmark_spirals: an implementation of the surge-sway-yaw
restriction of MODELS.md section 1 written from the spec alone (not from the engine), used
to make the data and to fit it with SciPy.

  simulate <dir> [a|b]      spiral and zigzag runs of the reference tugboat: <dir>/run<k>.csv
                            (t, c_L, c_R, x, y, psi with psi logged wrapped to (-pi, pi]);
                            run set a (5 runs) or b (6 other runs, other noise), named in
                            <dir>/runs.txt for the fit
  fit <dir> <starts.json> [variant]
                            scipy.optimize.least_squares (trust-region reflective, SciPy's
                            default tolerances) from each start; JSON on stdout: per start the
                            estimate, cost, evaluations and time; variant: trf (default), jac,
                            nobounds, dogbox or lm (VARIANTS)

The fit frees the 15 parameters of FREE (the thrust coefficients among them); the others stay
at their true values. Residuals are x, y and psi (unwrapped measurement against the simulated
heading) over every sample, each run weighted by 1/sqrt(samples) as the engine's configured
weights do, fixed (no re-estimated noise weights). Bounds are the signs a user knows: damping
and added mass <= 0, inertia and thrust slopes >= 0, offsets free. The Jacobian is SciPy's
2-point finite differences. The RK4 integrator is compiled by numba (Debian python3-numba) when
importable, plain Python otherwise (about 100x slower).
"""
import json
import os
import sys
import time

import numpy as np
from scipy.optimize import least_squares

os.environ.setdefault("NUMBA_CACHE_DIR", os.path.join(
    os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "vesselid_3dof_numba"))
try:
    from numba import njit
except ImportError:
    def njit(*args, **kwargs):
        if len(args) == 1 and callable(args[0]):
            return args[0]
        return lambda f: f

# Reference vessel (MODELS.md section 1), in surge, sway and yaw.
M_KG, LY, AX, AY, RHO_AIR = 11.0, 0.06, 0.05, 0.18, 1.225
TRUTH = {"Iz": 0.80, "Xudot": -1.0946, "Yvdot": -1.0536, "Yrdot": -1.4353, "Xu": -5.6128,
         "Yv": -3.5059, "Yr": -0.0001, "Nv": -1.0005, "Nr": -0.1039, "Xuu": -2.3136,
         "Yvv": -3.9310, "Nrr": -0.2605, "Nrdot": -0.0474, "C_DA": 0.6487, "L_TS": 10.2,
         "L_TO": 0.10, "R_TS": 9.8, "R_TO": -0.10}
ORDER = list(TRUTH)  # kernel order
FREE = ["Iz", "Xudot", "Yvdot", "Yrdot", "Xu", "Yv", "Yr", "Nv", "Nr", "Xuu", "Yvv", "Nrr",
        "L_TO", "R_TS", "R_TO"]
# Sign bounds: (lower, upper), None for none.
BOUNDS = {name: (None, 0.0) for name in FREE}
BOUNDS.update({"Iz": (0.0, None), "R_TS": (0.0, None), "L_TO": (None, None),
               "R_TO": (None, None), "Yr": (-1.0, 1.0)})
STEP, SAMPLE = 0.02, 0.1  # RK4 step and log interval, s

# Runs: (duration s, mean command, differential, zigzag period s or 0 for a spiral).
RUN_SETS = {
    "a": [(60.0, 0.6, 0.12, 0.0), (60.0, 0.5, -0.15, 0.0), (50.0, 0.8, 0.08, 0.0),
          (60.0, 0.6, 0.2, 20.0), (40.0, 0.4, 0.25, 0.0)],
    # Zigzags of other periods and amplitudes, turns the other way, slower and faster.
    "b": [(50.0, 0.7, 0.10, 12.0), (60.0, 0.45, 0.2, 30.0), (45.0, 0.9, -0.1, 0.0),
          (60.0, 0.55, 0.05, 8.0), (40.0, 0.3, -0.25, 0.0), (50.0, 0.65, 0.18, 20.0)],
}
NOISE_SEED = {"a": 7, "b": 8}
RUNS = RUN_SETS["a"]


@njit(cache=True)
def derivative(p, x, c_l, c_r, out):
    """x = [X, Y, psi, u, v, r]; p in ORDER."""
    iz, xudot, yvdot, yrdot, xu, yv, yr, nv, nr, xuu, yvv, nrr, nrdot, c_da, l_ts, l_to, \
        r_ts, r_to = p
    psi, u, v, r = x[2], x[3], x[4], x[5]
    m11 = M_KG - xudot
    m22 = M_KG - yvdot
    m23 = -yrdot
    m33 = iz - nrdot
    # Kirchhoff form: [h1; h2] = M nu, C nu = [w x h1; w x h2 + v1 x h1], w = [0, 0, r].
    h1x, h1y = m11 * u, m22 * v + m23 * r
    cor_u, cor_v, cor_r = -r * h1y, r * h1x, u * h1y - v * h1x
    d_u = -(xu * u + xuu * abs(u) * u)
    d_v = -(yv * v + yr * r + yvv * abs(v) * v)
    d_r = -(nv * v + nr * r + nrr * abs(r) * r)
    air = -0.5 * RHO_AIR * c_da
    f_l = l_ts * c_l + l_to
    f_r = r_ts * c_r + r_to
    fu = f_l + f_r + air * AX * abs(u) * u - cor_u - d_u
    fv = air * AY * abs(v) * v - cor_v - d_v
    fr = LY * (f_l - f_r) - cor_r - d_r
    det = m22 * m33 - m23 * m23
    c, s = np.cos(psi), np.sin(psi)
    out[0] = u * c - v * s
    out[1] = u * s + v * c
    out[2] = r
    out[3] = fu / m11
    out[4] = (m33 * fv - m23 * fr) / det
    out[5] = (m22 * fr - m23 * fv) / det


@njit(cache=True)
def simulate_run(p, duration, mean, diff, period):
    """Outputs x, y, psi at every log time, shape (samples, 3)."""
    per_sample = int(round(SAMPLE / STEP))
    steps = int(round(duration / STEP))
    out = np.empty((steps // per_sample + 1, 3))
    x = np.zeros(6)
    k1, k2, k3, k4, tmp = np.empty(6), np.empty(6), np.empty(6), np.empty(6), np.empty(6)
    out[0, :] = x[:3]
    for k in range(steps):
        t = k * STEP
        # The zigzag switches on a log time, so that the log's zero-order hold is the command.
        d = diff if period == 0.0 else diff * np.sign(np.sin(2 * np.pi * (t + 1e-6) / period))
        c_l, c_r = mean + d, mean - d
        derivative(p, x, c_l, c_r, k1)
        tmp[:] = x + 0.5 * STEP * k1
        derivative(p, tmp, c_l, c_r, k2)
        tmp[:] = x + 0.5 * STEP * k2
        derivative(p, tmp, c_l, c_r, k3)
        tmp[:] = x + STEP * k3
        derivative(p, tmp, c_l, c_r, k4)
        x += STEP / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        if (k + 1) % per_sample == 0:
            out[(k + 1) // per_sample, :] = x[:3]
    return out


def commands(run, t):
    duration, mean, diff, period = run
    d = diff if period == 0.0 else diff * np.sign(np.sin(2 * np.pi * (t + 1e-6) / period))
    return mean + d + 0 * t, mean - d + 0 * t


def parameter_vector(values):
    return np.array([values.get(name, TRUTH[name]) for name in ORDER], dtype=float)


def use_run_set(name):
    global RUNS
    RUNS = RUN_SETS[name]


def write_runs(folder, run_set):
    use_run_set(run_set)
    with open(f"{folder}/runs.txt", "w") as f:
        f.write(run_set)
    rng = np.random.default_rng(NOISE_SEED[run_set])
    for i, run in enumerate(RUNS):
        y = simulate_run(parameter_vector(TRUTH), *run)
        t = np.arange(len(y)) * SAMPLE
        c_l, c_r = commands(run, t)
        x_m = y[:, 0] + 0.02 * rng.standard_normal(len(t))
        y_m = y[:, 1] + 0.02 * rng.standard_normal(len(t))
        psi = y[:, 2] + np.radians(0.2) * rng.standard_normal(len(t))
        psi = np.angle(np.exp(1j * psi))  # logged wrapped, as a compass gives it
        with open(f"{folder}/run{i}.csv", "w") as f:
            f.write("t,c_L,c_R,x,y,psi\n")
            for row in zip(t, c_l, c_r, x_m, y_m, psi):
                f.write(",".join(f"{v:.9g}" for v in row) + "\n")
        print(f"run{i}: {run[0]:.0f} s, heading turned {y[-1, 2] / (2 * np.pi):+.2f} turns",
              file=sys.stderr)


def read_runs(folder):
    use_run_set(open(f"{folder}/runs.txt").read().strip())
    data = []
    for i in range(len(RUNS)):
        d = np.genfromtxt(f"{folder}/run{i}.csv", delimiter=",", names=True)
        data.append(np.column_stack([d["x"], d["y"], np.unwrap(d["psi"])]))
    return data


def residuals(theta, data):
    values = dict(zip(FREE, theta))
    p = parameter_vector(values)
    res = []
    for run, measured in zip(RUNS, data):
        y = simulate_run(p, *run)
        res.append(((y - measured) / np.sqrt(measured.size)).ravel())
    out = np.concatenate(res)
    return np.where(np.isfinite(out), out, 1e3)


# SciPy's solvers compared on the same starts (docs/benchmarks.md, "Why the local solve loses
# from far"): trf as SciPy's defaults, trf with x_scale='jac', trf without bounds, dogbox, and
# MINPACK's lm (which takes no bounds).
VARIANTS = {"trf": {}, "jac": {"x_scale": "jac"}, "nobounds": {"bounds": None},
            "dogbox": {"method": "dogbox"}, "lm": {"method": "lm", "bounds": None}}


def fit(folder, starts_path, variant="trf"):
    data = read_runs(folder)
    starts = json.load(open(starts_path))
    lower = np.array([-np.inf if BOUNDS[n][0] is None else BOUNDS[n][0] for n in FREE])
    upper = np.array([np.inf if BOUNDS[n][1] is None else BOUNDS[n][1] for n in FREE])
    residuals(parameter_vector(TRUTH)[[ORDER.index(n) for n in FREE]], data)  # compile
    results = []
    for start in starts:
        x0 = np.array([start[n] for n in FREE])
        begin = time.perf_counter()
        cpu = time.process_time()
        options = {"method": "trf", "bounds": (lower, upper)}
        options.update(VARIANTS[variant])
        if options["bounds"] is None:
            del options["bounds"]
        sol = least_squares(residuals, x0, args=(data,), **options)
        results.append({"estimate": dict(zip(FREE, sol.x.tolist())), "cost": sol.cost,
                        "evaluations": int(sol.nfev), "status": int(sol.status),
                        "seconds": time.perf_counter() - begin,
                        "cpu_seconds": time.process_time() - cpu})
    json.dump({"truth": {n: TRUTH[n] for n in FREE}, "results": results}, sys.stdout)


if __name__ == "__main__":
    if sys.argv[1] == "simulate":
        write_runs(sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else "a")
    else:
        fit(sys.argv[2], sys.argv[3], sys.argv[4] if len(sys.argv) > 4 else "trf")
