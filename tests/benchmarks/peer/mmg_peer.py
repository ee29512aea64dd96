#!/usr/bin/env python3
"""SciPy reference peer for the MMG benchmark (mmg_benchmark.py).

Written from the MMG standard model's equations as docs/models.md restates them (Yasukawa &
Yoshimura 2015) and the data conventions of docs/data.md, not from the engine's code. It reads
configs/mmg_kvlcc2.yaml (the subset it uses: the ship's dimensions, the first stage's free,
fixed and per-experiment parameters and free initial states, the training set, the
experiments' files and `degrees:` columns) and the CSV files `vesselid simulate` writes, and
identifies the stage by output error, as a user would script it:

  * RK4, one step per sample interval, the inputs (rudder, propeller rate) interpolated
    linearly at the step's middle;
  * residuals: simulated minus measured x, y, psi (rad, unwrapped) and U at every sample, each
    channel weighted by 1 / its noise level (the SD of the record's second differences / sqrt 6,
    pooled over the runs), each run by 1/sqrt(its samples);
  * unknowns: the stage's free parameters, one rudder bias per run, the six initial states per
    run (started from the data: x, y, psi at t0, u = U at t0, v = 0, r from the first second's
    heading slope);
  * scipy.optimize.least_squares with its defaults ('trf', '2-point' Jacobian, tolerances
    1e-8) and the stage's bounds.

  mmg_peer.py <config.yaml> --data <dir> [--json out]

Output: the estimates (shared, per run), cost, evaluations, `solve_seconds` (least_squares,
wall) and `setup_seconds` (imports, reading, compiling).
"""
import argparse
import json
import math
import os
import time

T_START = time.perf_counter()

import numpy as np  # noqa: E402
import yaml  # noqa: E402
from scipy.optimize import least_squares  # noqa: E402

os.environ.setdefault("NUMBA_CACHE_DIR", os.path.join(
    os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "vesselid_peer_numba"))
try:
    from numba import njit

    BACKEND = "numba"
except ImportError:
    BACKEND = "python"

    def njit(*args, **kwargs):
        if len(args) == 1 and callable(args[0]):
            return args[0]
        return lambda f: f

# The KVLCC2's coefficients (Yasukawa & Yoshimura 2015, Tables 2-4), in kernel order.
NAMES = ["R0", "X_vv", "X_vr", "X_rr", "X_vvvv", "Y_v", "Y_r", "Y_vvv", "Y_vvr", "Y_vrr",
         "Y_rrr", "N_v", "N_r", "N_vvv", "N_vvr", "N_vrr", "N_rrr", "m_x", "m_y", "J_z", "t_P",
         "w_P0", "k_0", "k_1", "k_2", "x_P", "C_1", "C_2_plus", "C_2_minus", "t_R", "a_H", "x_H",
         "epsilon", "kappa", "l_R", "gamma_R_plus", "gamma_R_minus", "f_alpha", "delta_0"]
KVLCC2 = [0.022, -0.040, 0.002, 0.011, 0.771, -0.315, 0.083, -1.607, 0.379, -0.391, 0.008,
          -0.137, -0.049, -0.030, -0.294, 0.055, -0.013, 0.022, 0.223, 0.011, 0.220, 0.40,
          0.2931, -0.2753, -0.1385, -0.48, 2.0, 1.6, 1.1, 0.387, 0.312, -0.464, 1.09, 0.50,
          -0.710, 0.640, 0.395, 2.747, 0.0]
# Ship: L, d, displacement, x_G, k_zz/L, D_P, A_R, H_R, x_R/L, rho (the 7 m model's).
SHIP_KEYS = ["length", "draft", "displacement", "centre_of_gravity", "radius_of_gyration",
             "propeller_diameter", "rudder_area", "rudder_height", "rudder_position",
             "water_density"]
SHIP_DEFAULT = [7.0, 0.455, 3.2724, 0.245, 0.25, 0.216, 0.0539, 0.345, -0.5, 1000.0]


@njit(cache=True)
def rhs(x, delta, n, p, s, dx):
    """MMG right-hand side; x = [x0, y0, psi, u, v, r]. False outside the model's domain."""
    L, d, disp, xg, kzz, dp, ar, hr, xr, rho = s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7], s[8], s[9]
    u, v, r = x[3], x[4], x[5]
    if not (u > 0.0) or not (n > 0.0):
        return False
    m = rho * disp
    half = 0.5 * rho * L * L * d
    U2 = u * u + v * v
    U = math.sqrt(U2)
    vn = v / U
    rn = r * L / U
    beta = math.atan2(-v, u)
    XH = -p[0] + p[1] * vn * vn + p[2] * vn * rn + p[3] * rn * rn + p[4] * vn ** 4
    YH = (p[5] * vn + p[6] * rn + p[7] * vn ** 3 + p[8] * vn * vn * rn + p[9] * vn * rn * rn +
          p[10] * rn ** 3)
    NH = (p[11] * vn + p[12] * rn + p[13] * vn ** 3 + p[14] * vn * vn * rn + p[15] * vn * rn * rn +
          p[16] * rn ** 3)
    q = 0.5 * rho * L * d * U2
    # propeller
    bp = beta - p[25] * rn
    c2 = p[27] if bp > 0.0 else p[28]
    wake = (1.0 - p[21]) * (1.0 + (1.0 - math.exp(-p[26] * abs(bp))) * (c2 - 1.0))
    J = u * wake / (n * dp)
    KT = p[22] + p[23] * J + p[24] * J * J
    XP = (1.0 - p[20]) * rho * n * n * dp ** 4 * KT
    # rudder
    arg = 1.0 + 8.0 * KT / (math.pi * J * J)
    if not (arg > 0.0):
        return False
    eta = dp / hr
    uR = p[32] * u * wake * math.sqrt(eta * (1.0 + p[33] * (math.sqrt(arg) - 1.0)) ** 2 + 1.0 - eta)
    bR = beta - p[34] * rn
    gam = p[35] if bR > 0.0 else p[36]
    vR = U * gam * bR
    de = delta + p[38]
    aR = de - math.atan2(vR, uR)
    FN = 0.5 * rho * ar * (uR * uR + vR * vR) * p[37] * math.sin(aR)
    X = q * XH + XP - (1.0 - p[29]) * FN * math.sin(de)
    Y = q * YH - (1.0 + p[30]) * FN * math.cos(de)
    N = q * L * NH - (xr * L + p[30] * p[31] * L) * FN * math.cos(de)
    mx, my, jz = half * p[17], half * p[18], half * L * L * p[19]
    izg = m * (kzz * L) ** 2
    c, sn = math.cos(x[2]), math.sin(x[2])
    dx[0] = u * c - v * sn
    dx[1] = u * sn + v * c
    dx[2] = r
    dx[3] = (X + (m + my) * v * r + xg * m * r * r) / (m + mx)
    a11, a12, a22 = m + my, xg * m, izg + xg * xg * m + jz
    b1, b2 = Y - (m + mx) * u * r, N - xg * m * u * r
    det = a11 * a22 - a12 * a12
    dx[4] = (a22 * b1 - a12 * b2) / det
    dx[5] = (a11 * b2 - a12 * b1) / det
    return True


@njit(cache=True)
def simulate(p, s, x0, t, delta, n, out):
    """RK4, one step per sample interval, inputs linear (midpoint the mean); out[k] =
    [x, y, psi, U] at sample k. False when the simulation leaves the domain."""
    x = x0.copy()
    k1, k2, k3, k4, xs = np.empty(6), np.empty(6), np.empty(6), np.empty(6), np.empty(6)
    for k in range(t.shape[0]):
        out[k, 0], out[k, 1], out[k, 2] = x[0], x[1], x[2]
        out[k, 3] = math.sqrt(x[3] * x[3] + x[4] * x[4])
        if k + 1 == t.shape[0]:
            break
        h = t[k + 1] - t[k]
        dm, nm = 0.5 * (delta[k] + delta[k + 1]), 0.5 * (n[k] + n[k + 1])
        ok = rhs(x, delta[k], n[k], p, s, k1)
        for i in range(6):
            xs[i] = x[i] + 0.5 * h * k1[i]
        ok = ok and rhs(xs, dm, nm, p, s, k2)
        for i in range(6):
            xs[i] = x[i] + 0.5 * h * k2[i]
        ok = ok and rhs(xs, dm, nm, p, s, k3)
        for i in range(6):
            xs[i] = x[i] + h * k3[i]
        ok = ok and rhs(xs, delta[k + 1], n[k + 1], p, s, k4)
        if not ok:
            return False
        for i in range(6):
            x[i] += h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i])
    return True


def noise_level(v):
    """SD of the white noise on a smooth record: SD of second differences / sqrt(6)."""
    d2 = np.diff(v, 2)
    return float(np.std(d2) / math.sqrt(6.0))


def load(config_path, data_dir):
    with open(config_path) as f:
        config = yaml.safe_load(f)
    model = config["model"]
    ship = np.array([float(model.get(k, v)) for k, v in zip(SHIP_KEYS, SHIP_DEFAULT)])
    stage = config["stages"][0]
    defaults = config.get("experiment_defaults", {})
    degrees = set(defaults.get("degrees", []))
    training = config["sets"][stage["experiments"]] if isinstance(stage["experiments"], str) \
        else stage["experiments"]
    files = {e["name"]: e["file"] for e in config["experiments"]}
    runs = []
    for name in training:
        table = np.genfromtxt(os.path.join(data_dir, files[name]), delimiter=",", names=True)
        column = lambda c: np.array(table[c], dtype=float)  # noqa: E731
        scale = lambda c: math.pi / 180.0 if c in degrees else 1.0  # noqa: E731
        run = {"name": name, "t": column("t"), "x": column("x"), "y": column("y"),
               "psi": np.unwrap(column("psi") * scale("psi")), "U": column("U"),
               "delta": column("delta") * scale("delta"), "n": column("n")}
        runs.append(run)
    return ship, stage, runs


def identify(ship, stage, runs):
    params = stage["parameters"]
    p = np.array(KVLCC2)
    free, lower, upper = [], [], []
    for name, spec in params.items():
        spec = spec or {}
        i = NAMES.index(name)
        if "start" in spec:
            p[i] = spec["start"]
        if spec.get("role", "free") == "free":
            free.append(i)
            lower.append(spec.get("lower", -np.inf))
            upper.append(spec.get("upper", np.inf))
    bias = params.get("delta_0", {}) or {}
    sigma = {c: np.sqrt(np.mean([noise_level(r[c]) ** 2 for r in runs])) for c in
             ["x", "y", "psi", "U"]}
    # unknowns: free shared, then per run [delta_0, x0 (6)]
    theta0 = [p[i] for i in free]
    lo, hi = list(lower), list(upper)
    for r in runs:
        k = max(1, int(round(1.0 / (r["t"][1] - r["t"][0]))))
        rate = (r["psi"][k] - r["psi"][0]) / (r["t"][k] - r["t"][0])
        theta0 += [bias.get("start", 0.0), r["x"][0], r["y"][0], r["psi"][0], r["U"][0], 0.0, rate]
        lo += [bias.get("lower", -np.inf)] + [-np.inf] * 6
        hi += [bias.get("upper", np.inf)] + [np.inf] * 6
    theta0 = np.clip(np.array(theta0), np.array(lo) + 1e-12, np.array(hi) - 1e-12)
    nf = len(free)
    outs = [np.empty((len(r["t"]), 4)) for r in runs]
    weights = np.array([1.0 / sigma[c] for c in ["x", "y", "psi", "U"]])

    def residuals(theta):
        q = p.copy()
        q[free] = theta[:nf]
        res = []
        for j, r in enumerate(runs):
            block = theta[nf + 7 * j: nf + 7 * (j + 1)]
            q[38] = block[0]
            measured = np.column_stack([r["x"], r["y"], r["psi"], r["U"]])
            if simulate(q, ship, block[1:].copy(), r["t"], r["delta"], r["n"], outs[j]):
                e = (outs[j] - measured) * weights
            else:
                e = np.full(measured.shape, 1e3)
            res.append(e.ravel() / math.sqrt(len(r["t"])))
        return np.concatenate(res)

    residuals(theta0)  # compiles the kernel before the clock starts
    start = time.perf_counter()
    solution = least_squares(residuals, theta0, bounds=(lo, hi))
    solve_seconds = time.perf_counter() - start
    estimates = {NAMES[i]: float(solution.x[k]) for k, i in enumerate(free)}
    biases = {r["name"]: float(solution.x[nf + 7 * j]) for j, r in enumerate(runs)}
    return {"backend": BACKEND, "estimates": estimates, "delta_0": biases,
            "cost": float(solution.cost), "nfev": int(solution.nfev),
            "njev": int(solution.njev or 0), "status": int(solution.status),
            "message": solution.message, "solve_seconds": solve_seconds,
            "noise": {c: float(v) for c, v in sigma.items()}}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("config")
    parser.add_argument("--data", required=True)
    parser.add_argument("--json")
    args = parser.parse_args()
    ship, stage, runs = load(args.config, args.data)
    result = identify(ship, stage, runs)
    result["setup_seconds"] = time.perf_counter() - T_START - result["solve_seconds"]
    text = json.dumps(result, indent=2)
    if args.json:
        with open(args.json, "w") as f:
            f.write(text + "\n")
    else:
        print(text)


if __name__ == "__main__":
    main()
