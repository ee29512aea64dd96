#!/usr/bin/env python3
"""SciPy reference peer for the Nomoto cases of the paired benchmark (compare.py).

Written from the model equations (../shared/spec/MODELS.md section 2) and the data
conventions of docs/data.md, not from the engine's code. It reads a vesselid config (the subset these cases
use) and the CSV files `vesselid simulate` writes, and identifies the stage by output error:

  * models: nomoto first_order   (psi' = r,  T r' + r = K (delta + delta_0))
            nomoto second_order  (psi' = K (xi1 + T3 xi2), xi1' = xi2,
                                  xi2' = (delta + delta_0 - xi1 - (T1 + T2) xi2) / (T1 T2))
  * RK4 with the engine's step rule: each sample interval in equal steps of at most
    `integration.max_step` (default: the median interval); inputs at the step's start, middle
    and end interpolated as the experiment says (zero_order_hold, linear, or cubic Hermite with
    Catmull-Rom slopes; default linear; end values held outside the samples);
  * residuals: simulated minus measured (unwrapped) heading at every sample, each experiment
    weighted by 1/sqrt(its samples) (the engine's normalize_by_length);
  * unknowns: the stage's free parameters, per_experiment parameters (one per experiment) and
    free_initial_states (per experiment, started from the data: psi at t0, r from the first
    second's slope, other states 0);
  * solver: scipy.optimize.least_squares, method 'trf', finite-difference Jacobian ('2-point'),
    x_scale 'jac', ftol = xtol = 1e-12, gtol = 1e-14 (the engine's Ceres tolerances: a noise-free
    case ends at a cost near 1e-18, and gtol = 1e-10 stopped patrol starts 5 % off).

The integrator is compiled with numba when it is importable (Debian python3-numba), plain
Python otherwise (correct, about 100x slower); `backend` in the output says which.

  nomoto_peer.py <config.yaml> --data <dir> [--stage NAME] [--starts starts.json] [--json out]
                 [--tolerances ftol,xtol,gtol]

starts.json: a list of {parameter: start value}, each one solve from the config's starts with
those replaced (default: one solve from the config). Output (stdout or --json): per start the
estimates, cost, evaluations, termination and `solve_seconds` (the least_squares call, wall)
and `solve_cpu_seconds`; `setup_seconds` (imports, reading, compiling).
"""
import argparse
import csv
import json
import math
import os
import sys
import time

T_START = time.perf_counter()

import numpy as np  # noqa: E402
import yaml  # noqa: E402
from scipy.optimize import least_squares  # noqa: E402

# numba's compiled cache outside the source tree unless the caller chose a place.
os.environ.setdefault("NUMBA_CACHE_DIR", os.path.join(
    os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "vesselid_peer_numba"))
try:
    from numba import njit

    BACKEND = "numba"
except ImportError:  # plain Python: the same kernel, interpreted
    BACKEND = "python"

    def njit(*args, **kwargs):
        if len(args) == 1 and callable(args[0]):
            return args[0]
        return lambda f: f

MODELS = {
    # type: (states, parameter names in kernel order, model id)
    "first_order": (["psi", "r"], ["T", "K", "delta_0"], 0),
    "second_order": (["psi", "xi1", "xi2"], ["T1", "T2", "T3", "K", "delta_0"], 1),
}
DEFAULTS = {"delta_0": 0.0}


@njit(cache=True)
def _rhs(model, x, u, p, dx):
    if model == 0:  # first order: x = [psi, r]
        dx[0] = x[1]
        dx[1] = (p[1] * (u + p[2]) - x[1]) / p[0]
    else:  # second order: x = [psi, xi1, xi2]
        dx[0] = p[3] * (x[1] + p[2] * x[2])
        dx[1] = x[2]
        dx[2] = (u + p[4] - x[1] - (p[0] + p[1]) * x[2]) / (p[0] * p[1])


@njit(cache=True)
def simulate(model, p, x0, u, substeps, h, psi_out):
    """RK4 over the nodes: u holds per step (start, middle, end) inputs; psi_out[k] = psi at
    node k. Returns False when the state stops being finite."""
    n = x0.shape[0]
    x = x0.copy()
    xs = np.empty(n)
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    psi_out[0] = x[0]
    j = 0
    for k in range(substeps.shape[0]):
        hk = h[k]
        for _ in range(substeps[k]):
            _rhs(model, x, u[3 * j], p, k1)
            for i in range(n):
                xs[i] = x[i] + 0.5 * hk * k1[i]
            _rhs(model, xs, u[3 * j + 1], p, k2)
            for i in range(n):
                xs[i] = x[i] + 0.5 * hk * k2[i]
            _rhs(model, xs, u[3 * j + 1], p, k3)
            for i in range(n):
                xs[i] = x[i] + hk * k3[i]
            _rhs(model, xs, u[3 * j + 2], p, k4)
            for i in range(n):
                x[i] += hk / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i])
            j += 1
        if not math.isfinite(x[0]):
            return False
        psi_out[k + 1] = x[0]
    return True


def interpolate(t, v, method, times, left_limit=False):
    """Input at `times` between samples (t, v); end values held outside the samples."""
    n = len(t)
    if left_limit:  # the sample interval containing each time, switches seen from the left
        k = np.searchsorted(t, times, side="left") - 1
    else:
        k = np.searchsorted(t, times, side="right") - 1
    k = np.clip(k, 0, n - 2)
    h = t[k + 1] - t[k]
    s = np.clip((times - t[k]) / h, 0.0, 1.0)
    if method == "zero_order_hold":
        out = v[k].copy()
    elif method == "linear":
        out = v[k] + s * (v[k + 1] - v[k])
    elif method == "cubic":  # Hermite, Catmull-Rom slopes (one-sided at the ends)
        lo = np.maximum(np.arange(n) - 1, 0)
        hi = np.minimum(np.arange(n) + 1, n - 1)
        m = (v[hi] - v[lo]) / (t[hi] - t[lo])
        s2, s3 = s * s, s * s * s
        out = ((2 * s3 - 3 * s2 + 1) * v[k] + (s3 - 2 * s2 + s) * h * m[k] +
               (-2 * s3 + 3 * s2) * v[k + 1] + (s3 - s2) * h * m[k + 1])
    else:
        raise ValueError("unknown interpolation '%s'" % method)
    out[times <= t[0]] = v[0]
    out[times > t[-1] if left_limit else times >= t[-1]] = v[-1]
    return out


def read_csv(path):
    """Columns by name; an empty field is a missing sample (NaN)."""
    with open(path, newline="") as f:
        header = next(csv.reader(f))
    try:  # numpy's C reader when every field is filled
        table = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        return {name: table[:, i] for i, name in enumerate(header)}
    except ValueError:
        pass
    with open(path, newline="") as f:
        rows = list(csv.reader(f))[1:]
    cols = {name: [] for name in header}
    for row in rows:
        for name, field in zip(header, row):
            cols[name].append(float(field) if field.strip() else math.nan)
    return {name: np.array(values) for name, values in cols.items()}


class Experiment:
    def __init__(self, spec, data_dir, max_step, states):
        self.name = spec["name"]
        cols = read_csv(os.path.join(data_dir, spec["file"]))
        degrees = set(spec.get("degrees", []))
        t = cols["t"]
        delta_col = spec["inputs"]["delta"]
        psi_col = spec["outputs"]["psi"]
        to_rad = lambda col: np.deg2rad(cols[col]) if col in degrees else cols[col]  # noqa: E731
        delta, psi = to_rad(delta_col), to_rad(psi_col)
        keep_u = np.isfinite(delta)
        self.mask = np.isfinite(psi)
        psi_unwrapped = np.full_like(psi, math.nan)
        psi_unwrapped[self.mask] = np.unwrap(psi[self.mask])
        self.psi = psi_unwrapped[self.mask]
        self.weight = 1.0 / math.sqrt(self.mask.sum())
        # Equal RK4 steps of at most max_step per sample interval.
        intervals = np.diff(t)
        step = max_step if max_step > 0 else float(np.median(intervals))
        self.substeps = np.maximum(1, np.ceil(intervals / step - 1e-6)).astype(np.int64)
        self.h = intervals / self.substeps
        first = np.repeat(np.cumsum(self.substeps) - self.substeps, self.substeps)
        within = np.arange(len(first)) - first  # step index inside its sample interval
        hs = np.repeat(self.h, self.substeps)
        starts = np.repeat(t[:-1], self.substeps) + within * hs
        method = spec.get("interpolation", {}).get("delta", "linear")
        tu, vu = t[keep_u], delta[keep_u]
        u = np.empty(3 * len(starts))
        u[0::3] = interpolate(tu, vu, method, starts)
        u[1::3] = interpolate(tu, vu, method, starts + 0.5 * hs)
        u[2::3] = interpolate(tu, vu, method, starts + hs, left_limit=True)
        self.u = u
        self.psi_sim = np.empty(len(t))
        # Initial states: psi at t0, r from the slope over the first second, others 0.
        t_psi = t[self.mask]
        first = t_psi <= t_psi[0] + 1.0 + 1e-9
        rate = 0.0
        if first.sum() >= 2:
            rate = float(np.polyfit(t_psi[first], self.psi[first], 1)[0])
        guess = {"psi": float(self.psi[0]), "r": rate}
        self.x0 = np.array([guess.get(s, 0.0) for s in states])


def merged(defaults, spec):
    out = dict(defaults)
    for key, value in spec.items():
        out[key] = dict(out[key], **value) if isinstance(value, dict) and key in out else value
    return out


class Problem:
    def __init__(self, config, data_dir, stage_name=None):
        model = config["model"]
        if model.get("family") != "nomoto" or model.get("type") not in MODELS:
            raise SystemExit("peer: model %s not implemented" % model)
        self.states, self.names, self.model_id = MODELS[model["type"]]
        stages = [s for s in config["stages"] if s.get("type", "output_error") == "output_error"]
        stage = next(s for s in stages if stage_name in (None, s["name"]))
        sets = config.get("sets", {})
        defaults = config.get("experiment_defaults", {})
        specs = {e["name"]: merged(defaults, e) for e in config["experiments"]}
        chosen = stage.get("experiments", list(specs))
        if isinstance(chosen, str):
            chosen = sets[chosen]
        max_step = float(stage.get("integration", {}).get("max_step", 0.0))
        self.experiments = [Experiment(specs[n], data_dir, max_step, self.states) for n in chosen]
        # Unknowns: shared free parameters, per-experiment ones, free initial states.
        self.params = stage["parameters"]
        self.free = [n for n in self.names if n in self.params
                     and self.params[n].get("role", "free") not in ("fixed", "per_experiment")]
        self.per_exp = [n for n in self.names if n in self.params
                        and self.params[n].get("role") == "per_experiment"]
        self.free_states = [self.states.index(s) for s in stage.get("free_initial_states", [])]
        self.fixed = {n: float(self.params.get(n, {}).get("start", DEFAULTS.get(n, math.nan)))
                      for n in self.names}

    def layout(self, starts):
        x0, lo, hi = [], [], []
        for n in self.free:
            x0.append(float(starts.get(n, self.params[n]["start"])))
            lo.append(float(self.params[n].get("lower", -np.inf)))
            hi.append(float(self.params[n].get("upper", np.inf)))
        for _ in self.experiments:
            for n in self.per_exp:
                x0.append(float(starts.get(n, self.params[n].get("start", DEFAULTS.get(n, 0.0)))))
                lo.append(float(self.params[n].get("lower", -np.inf)))
                hi.append(float(self.params[n].get("upper", np.inf)))
        for e in self.experiments:
            for s in self.free_states:
                x0.append(e.x0[s])
                lo.append(-np.inf)
                hi.append(np.inf)
        return np.array(x0), (np.array(lo), np.array(hi))

    def residuals(self, z):
        nf, npe, ns = len(self.free), len(self.per_exp), len(self.free_states)
        values = dict(self.fixed)
        values.update(zip(self.free, z[:nf]))
        out = []
        for j, e in enumerate(self.experiments):
            base = nf + j * npe
            values.update(zip(self.per_exp, z[base:base + npe]))
            p = np.array([values[n] for n in self.names])
            x0 = e.x0.copy()
            sbase = nf + len(self.experiments) * npe + j * ns
            x0[self.free_states] = z[sbase:sbase + ns]
            if not simulate(self.model_id, p, x0, e.u, e.substeps, e.h, e.psi_sim):
                out.append(np.full(len(e.psi), 1e10))
                continue
            out.append(e.weight * (e.psi_sim[e.mask] - e.psi))
        return np.concatenate(out)

    def initial_states(self, z):
        """Per experiment {state: value} at the unknowns z (the free ones from z)."""
        nf, ns = len(self.free), len(self.free_states)
        out = []
        for j, e in enumerate(self.experiments):
            x0 = e.x0.copy()
            sbase = nf + len(self.per_exp) * len(self.experiments) + j * ns
            x0[self.free_states] = z[sbase:sbase + ns]
            out.append({s: float(v) for s, v in zip(self.states, x0)})
        return out

    def solve(self, starts, tolerances=(1e-12, 1e-12, 1e-14)):
        z0, bounds = self.layout(starts)
        z0 = np.clip(z0, bounds[0], bounds[1])
        wall, cpu = time.perf_counter(), time.process_time()
        fit = least_squares(self.residuals, z0, jac="2-point", method="trf", bounds=bounds,
                            x_scale="jac", ftol=tolerances[0], xtol=tolerances[1],
                            gtol=tolerances[2])
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        nf = len(self.free)
        return {"start": {n: float(v) for n, v in zip(self.free, z0[:nf])},
                "estimates": {n: float(v) for n, v in zip(self.free, fit.x[:nf])},
                "per_experiment": {n: [float(fit.x[nf + j * len(self.per_exp) + i])
                                       for j in range(len(self.experiments))]
                                   for i, n in enumerate(self.per_exp)},
                "initial_states": self.initial_states(fit.x),
                "cost": float(fit.cost), "evaluations": int(fit.nfev),
                "jacobians": int(fit.njev or 0), "status": int(fit.status),
                "message": fit.message, "solve_seconds": wall, "solve_cpu_seconds": cpu}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("config")
    parser.add_argument("--data", required=True)
    parser.add_argument("--stage")
    parser.add_argument("--starts", help="JSON list of {parameter: start}")
    parser.add_argument("--json", help="write the result here (default stdout)")
    parser.add_argument("--tolerances", default="1e-12,1e-12,1e-14",
                        help="least_squares ftol,xtol,gtol (SciPy's defaults: 1e-8,1e-8,1e-8)")
    args = parser.parse_args()
    with open(args.config) as f:
        config = yaml.safe_load(f)
    tolerances = [float(v) for v in args.tolerances.split(",")]
    problem = Problem(config, args.data, args.stage)
    starts = [{}]
    if args.starts:
        with open(args.starts) as f:
            starts = json.load(f)
    z0, _ = problem.layout(starts[0])
    problem.residuals(z0)  # compiles (or loads the numba cache) before any timed solve
    setup = time.perf_counter() - T_START
    result = {"backend": BACKEND, "setup_seconds": setup,
              "unknowns": len(z0), "samples": int(sum(len(e.psi) for e in problem.experiments)),
              "tolerances": tolerances, "solves": [problem.solve(s, tolerances) for s in starts]}
    text = json.dumps(result, indent=1)
    if args.json:
        with open(args.json, "w") as f:
            f.write(text + "\n")
    else:
        print(text)


if __name__ == "__main__":
    sys.exit(main())
