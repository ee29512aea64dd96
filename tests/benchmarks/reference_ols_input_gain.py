#!/usr/bin/env python3
"""Reference peer for benchmark_mismatch: the plain least-squares fit a user would script.

Velocities and accelerations from Savitzky-Golay filters of the GNSS positions and the
heading on the GNSS grid of each segment; one ordinary least-squares regression per velocity
equation with the input-gain model's regressors (static thrust, no dead zone); then every
held-out segment simulated free from its filtered initial state (RK4 at the PWM hold) and its
u, v, r compared with the filtered ones and with the simulator's truth columns.

usage: reference_ols_input_gain.py campaign.csv held_out_ids training_ids
       (ids comma-separated) -> one JSON object on stdout
"""
import json
import sys

import numpy as np
from scipy.signal import savgol_filter

HALF_WIDTH, ORDER = 7, 4  # as the shipped configs' least_squares.smoothing


def read(path):
    data = np.genfromtxt(path, delimiter=",", names=True)
    return data


def segment_arrays(data, sid):
    rows = data[data["segment"] == sid]
    gnss = rows[~np.isnan(rows["n"])]
    ahrs = rows[~np.isnan(rows["heading"])]
    pwm = rows[~np.isnan(rows["pwm_L"])]
    t = gnss["t"]
    psi_all = np.unwrap(ahrs["heading"])
    psi = np.interp(t, ahrs["t"], psi_all)
    dt = np.median(np.diff(t))
    window = 2 * HALF_WIDTH + 1
    if len(t) < window + 2:
        return None
    n = savgol_filter(gnss["n"], window, ORDER)
    e = savgol_filter(gnss["e"], window, ORDER)
    ndot = savgol_filter(gnss["n"], window, ORDER, deriv=1, delta=dt)
    edot = savgol_filter(gnss["e"], window, ORDER, deriv=1, delta=dt)
    psi_s = savgol_filter(psi, window, ORDER)
    r = savgol_filter(psi, window, ORDER, deriv=1, delta=dt)
    c, s = np.cos(psi_s), np.sin(psi_s)
    u = c * ndot + s * edot
    v = -s * ndot + c * edot
    ud = savgol_filter(u, window, ORDER, deriv=1, delta=dt)
    vd = savgol_filter(v, window, ORDER, deriv=1, delta=dt)
    rd = savgol_filter(r, window, ORDER, deriv=1, delta=dt)
    # PWM held (zero-order hold) at the GNSS times.
    idx = np.searchsorted(pwm["t"], t, side="right") - 1
    idx = np.clip(idx, 0, len(pwm) - 1)
    ul, ur = pwm["pwm_L"][idx], pwm["pwm_R"][idx]
    truth = {k: np.interp(t, ahrs["t"], ahrs[k + "_true"]) for k in ("u", "v", "r")}
    # Drop the filter's edges, where it extrapolates.
    keep = slice(HALF_WIDTH, len(t) - HALF_WIDTH)
    return dict(t=t, n=n, e=e, psi=psi_s, u=u, v=v, r=r, ud=ud, vd=vd, rd=rd, ul=ul, ur=ur,
                truth=truth, keep=keep, pwm_t=pwm["t"], pwm_l=pwm["pwm_L"], pwm_r=pwm["pwm_R"])


def thrust_columns(ul, ur, difference):
    """s+, s+^2, s-, s-^2 summed (surge) or differenced (sway, yaw) over the propellers."""
    cols = []
    for f in (lambda x: np.maximum(x, 0), lambda x: np.maximum(x, 0) ** 2,
              lambda x: np.minimum(x, 0), lambda x: np.minimum(x, 0) ** 2):
        a, b = f(ul), f(ur)
        cols.append(a - b if difference else a + b)
    return cols


def regressors(u, v, r, ul, ur):
    one = np.ones_like(u)
    xu = [one, u, np.abs(u) * u, v * r, r * r] + thrust_columns(ul, ur, False)
    xv = [one, v, r, np.abs(v) * v, u * r, u * v] + thrust_columns(ul, ur, True)
    xr = [one, v, r, np.abs(r) * r, u * v, u * r] + thrust_columns(ul, ur, True)
    return [np.column_stack(x) for x in (xu, xv, xr)]


def fit(segments):
    rows = [[], [], []]
    targets = [[], [], []]
    for s in segments:
        k = s["keep"]
        xs = regressors(s["u"][k], s["v"][k], s["r"][k], s["ul"][k], s["ur"][k])
        for i, (x, y) in enumerate(zip(xs, (s["ud"][k], s["vd"][k], s["rd"][k]))):
            rows[i].append(x)
            targets[i].append(y)
    return [np.linalg.lstsq(np.vstack(rows[i]), np.concatenate(targets[i]), rcond=None)[0]
            for i in range(3)]


def free_run(theta, s, step=0.02):
    k0 = s["keep"].start
    t0, t1 = s["t"][k0], s["t"][s["keep"].stop - 1]
    x = np.array([s["u"][k0], s["v"][k0], s["r"][k0]])

    def pwm_at(t):
        j = max(0, np.searchsorted(s["pwm_t"], t, side="right") - 1)
        return s["pwm_l"][j], s["pwm_r"][j]

    def f(x, ul, ur):
        a = np.array([x[0]]), np.array([x[1]]), np.array([x[2]])
        xs = regressors(*a, np.array([ul]), np.array([ur]))
        return np.array([float(xs[i] @ theta[i]) for i in range(3)])

    times = s["t"][s["keep"]]
    out = [x.copy()]
    t = t0
    for target in times[1:]:
        while t < target - 1e-9:
            h = min(step, target - t)
            ul, ur = pwm_at(t)
            k1 = f(x, ul, ur)
            k2 = f(x + 0.5 * h * k1, ul, ur)
            k3 = f(x + 0.5 * h * k2, ul, ur)
            k4 = f(x + h * k3, ul, ur)
            x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            t += h
            if not np.all(np.isfinite(x)) or np.max(np.abs(x)) > 1e3:
                return None
        out.append(x.copy())
    return np.array(out)


def r2(pred, meas):
    sst = np.sum((meas - meas.mean()) ** 2)
    return 1 - np.sum((pred - meas) ** 2) / sst


def main():
    data = read(sys.argv[1])
    held = [int(i) for i in sys.argv[2].split(",")]
    train = [int(i) for i in sys.argv[3].split(",")]
    train_segments = [s for s in (segment_arrays(data, i) for i in train) if s is not None]
    theta = fit(train_segments)
    pred = {k: [] for k in "uvr"}
    filt = {k: [] for k in "uvr"}
    true = {k: [] for k in "uvr"}
    diverged = 0
    for sid in held:
        s = segment_arrays(data, sid)
        if s is None:
            continue
        run = free_run(theta, s)
        if run is None:
            diverged += 1
            continue
        for i, k in enumerate("uvr"):
            pred[k].append(run[:, i])
            filt[k].append(s[k][s["keep"]])
            true[k].append(s["truth"][k][s["keep"]])
    result = {"diverged": diverged}
    for k in "uvr":
        p, m, tr = (np.concatenate(x[k]) for x in (pred, filt, true))
        result[k] = {"r2": r2(p, m), "mae": float(np.mean(np.abs(p - m))),
                     "r2_truth": r2(p, tr), "mae_truth": float(np.mean(np.abs(p - tr)))}
    json.dump(result, sys.stdout)


if __name__ == "__main__":
    main()
