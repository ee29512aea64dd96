#!/usr/bin/env python3
"""Reference peer for benchmark_spirals: an implementation of the surge-sway-yaw
restriction of MODELS.md section 1 written from the spec alone (not from the engine), used
to make the data and to fit it with SciPy.

  simulate <dir>            spiral and zigzag runs of the reference tugboat: <dir>/run<k>.csv
                            (t, c_L, c_R, x, y, psi with psi logged wrapped to (-pi, pi])
  fit <dir> <starts.json>   scipy.optimize.least_squares (trust-region reflective) from each
                            start; JSON on stdout: per start the estimate, cost and time

The residuals are x, y and psi (unwrapped measurement against the simulated heading) over
every sample, each run weighted by 1/sqrt(samples) as the engine does.
"""
import json
import sys
import time

import numpy as np
from scipy.optimize import least_squares

# Reference vessel (MODELS.md section 1), in surge, sway and yaw.
M_KG, LY, AX, AY, RHO_AIR = 11.0, 0.06, 0.05, 0.18, 1.225
TRUTH = {"Iz": 0.80, "Xudot": -1.0946, "Yvdot": -1.0536, "Yrdot": -1.4353, "Xu": -5.6128,
         "Yv": -3.5059, "Yr": -0.0001, "Nv": -1.0005, "Nr": -0.1039, "Xuu": -2.3136,
         "Yvv": -3.9310, "Nrr": -0.2605}
FIXED = {"Nrdot": -0.0474, "C_DA": 0.6487, "L_TS": 10.2, "L_TO": 0.10, "R_TS": 9.8,
         "R_TO": -0.10}
NAMES = list(TRUTH)
STEP, SAMPLE = 0.02, 0.1  # RK4 step and log interval, s

# Runs: (duration s, mean command, differential, zigzag period s or 0 for a spiral).
RUNS = [(60.0, 0.6, 0.12, 0.0), (60.0, 0.5, -0.15, 0.0), (50.0, 0.8, 0.08, 0.0),
        (60.0, 0.6, 0.2, 20.0), (40.0, 0.4, 0.25, 0.0)]


def commands(run, t):
    duration, mean, diff, period = run
    # The zigzag switches on a log time, so that the log's zero-order hold is the command.
    d = diff if period == 0.0 else diff * np.sign(np.sin(2 * np.pi * (t + 1e-6) / period))
    return mean + d + 0 * t, mean - d + 0 * t


def derivative(p, x, c_l, c_r):
    """x = [X, Y, psi, u, v, r] with batch axis last; p a dict of arrays (batch) or floats."""
    px, py, psi, u, v, r = x
    m11 = M_KG - p["Xudot"]
    m22 = M_KG - p["Yvdot"]
    m23 = -p["Yrdot"]
    m33 = p["Iz"] - FIXED["Nrdot"]
    # Kirchhoff form: [h1; h2] = M nu, C nu = [w x h1; w x h2 + v1 x h1], w = [0, 0, r].
    h1x, h1y = m11 * u, m22 * v + m23 * r
    cor_u, cor_v, cor_r = -r * h1y, r * h1x, u * h1y - v * h1x
    d_u = -(p["Xu"] * u + p["Xuu"] * np.abs(u) * u)
    d_v = -(p["Yv"] * v + p["Yr"] * r + p["Yvv"] * np.abs(v) * v)
    d_r = -(p["Nv"] * v + p["Nr"] * r + p["Nrr"] * np.abs(r) * r)
    air = -0.5 * RHO_AIR * FIXED["C_DA"]
    f_l = FIXED["L_TS"] * c_l + FIXED["L_TO"]
    f_r = FIXED["R_TS"] * c_r + FIXED["R_TO"]
    fu = f_l + f_r + air * AX * np.abs(u) * u - cor_u - d_u
    fv = air * AY * np.abs(v) * v - cor_v - d_v
    fr = LY * (f_l - f_r) - cor_r - d_r
    det = m22 * m33 - m23 * m23
    c, s = np.cos(psi), np.sin(psi)
    return np.array([u * c - v * s, u * s + v * c, r, fu / m11, (m33 * fv - m23 * fr) / det,
                     (m22 * fr - m23 * fv) / det])


def simulate(p, run, batch=None):
    """Outputs x, y, psi at every log time; shape (samples, 3[, batch])."""
    duration = run[0]
    shape = (6,) if batch is None else (6, batch)
    x = np.zeros(shape)
    per_sample = int(round(SAMPLE / STEP))
    out = [x[:3].copy()]
    steps = int(round(duration / STEP))
    with np.errstate(all="ignore"):
        for k in range(steps):
            c_l, c_r = commands(run, k * STEP)  # held over the step
            k1 = derivative(p, x, c_l, c_r)
            k2 = derivative(p, x + 0.5 * STEP * k1, c_l, c_r)
            k3 = derivative(p, x + 0.5 * STEP * k2, c_l, c_r)
            k4 = derivative(p, x + STEP * k3, c_l, c_r)
            x = x + STEP / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            if (k + 1) % per_sample == 0:
                out.append(x[:3].copy())
    return np.array(out)


def write_runs(folder):
    rng = np.random.default_rng(7)
    for i, run in enumerate(RUNS):
        y = simulate(TRUTH, run)
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
    data = []
    for i in range(len(RUNS)):
        d = np.genfromtxt(f"{folder}/run{i}.csv", delimiter=",", names=True)
        data.append(np.column_stack([d["x"], d["y"], np.unwrap(d["psi"])]))
    return data


def residuals(theta_batch, data):
    """Residual vectors for a batch of parameter vectors (n_params, batch)."""
    p = {name: theta_batch[i] for i, name in enumerate(NAMES)}
    res = []
    for run, measured in zip(RUNS, data):
        y = simulate(p, run, theta_batch.shape[1])
        res.append(((y - measured[:, :, None]) / np.sqrt(measured.size)).reshape(-1, theta_batch.shape[1]))
    out = np.vstack(res)
    return np.where(np.isfinite(out), out, 1e3)


def fit(folder, starts_path):
    data = read_runs(folder)
    starts = json.load(open(starts_path))
    lower = np.array([-1e3 if TRUTH[n] < 0 else 1e-3 for n in NAMES])
    upper = np.array([-1e-6 if TRUTH[n] < 0 else 1e3 for n in NAMES])
    lower[NAMES.index("Yr")], upper[NAMES.index("Yr")] = -1.0, 1.0
    for name in ("Xudot", "Yvdot", "Yrdot"):
        lower[NAMES.index(name)], upper[NAMES.index(name)] = -10.0, 5.0

    def f(theta):
        return residuals(theta[:, None], data)[:, 0]

    def jac(theta):
        # Forward differences of every parameter in one batched simulation.
        h = 1e-6 * np.maximum(1.0, np.abs(theta))
        batch = np.tile(theta[:, None], (1, len(theta) + 1))
        batch[np.arange(len(theta)), np.arange(len(theta)) + 1] += h
        r = residuals(batch, data)
        return (r[:, 1:] - r[:, :1]) / h

    results = []
    for start in starts:
        x0 = np.clip(np.array([start[n] for n in NAMES]), lower + 1e-9, upper - 1e-9)
        begin = time.perf_counter()
        sol = least_squares(f, x0, jac=jac, bounds=(lower, upper), method="trf",
                            x_scale="jac", max_nfev=300, ftol=1e-12, xtol=1e-12, gtol=1e-12)
        results.append({"estimate": dict(zip(NAMES, sol.x.tolist())), "cost": sol.cost,
                        "seconds": time.perf_counter() - begin, "status": int(sol.status)})
    json.dump({"truth": TRUTH, "results": results}, sys.stdout)


if __name__ == "__main__":
    if sys.argv[1] == "simulate":
        write_runs(sys.argv[2])
    else:
        fit(sys.argv[2], sys.argv[3])
