#!/usr/bin/env python3
"""The filter-error method's cost and estimates beside output error's and a SciPy peer's.

For each seed a record of a quick vessel is simulated here (numpy, a linear yaw model in its
own state-space form, not the engine's simulator): second-order Nomoto dynamics driven by a
multisine rudder (15 deg RMS, periods 40 to 1.3 s) through a 1 s servo, white yaw-moment process noise, an AR(1) heading sensor
noise (tau 3 s, SD 0.002 rad) and 0.0005 rad of white heading noise, logged at 10 Hz for 600 s.
It is fitted three ways:

  oe    vesselid run, output error (the default stage)
  fe    vesselid run, `noise: {method: filter_error, measurement: {psi: {type: ar1, white: true}},
        process: {eta2: auto}}`
  peer  tests/benchmarks/peer_filter_error.py --ar1: the textbook filter-error method
        (steady-state gain, relaxation algorithm, finite-difference gradients) with its defaults

and the CPU time of each process (getrusage of the child), the estimates, their standard
errors and |error| / SE are printed. The engine's times include reading the record and writing
results.json (`--no-report`); the peer's is its fit's process time.

usage: filter_error_speed.py [--seeds N] [--binary build/vesselid]
"""
import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
T1, T2, T3, K = 2.0, 0.3, 0.2, -0.17
TRUTH = {"a1": 1 / T1 + 1 / T2, "a0": 1 / (T1 * T2), "b": K / (T1 * T2), "T3": T3}
NAMES = ["a1", "a0", "b", "T3"]


def simulate(seed, duration=600.0, rate=10.0, q=1e-6, tau=3.0, ar_sd=0.002, white=0.0005):
    """psi''' + a1 psi'' + a0 psi' = b (delta + T3 delta'), in the rates form, at 100 Hz."""
    rng = np.random.default_rng(seed)
    h = 0.01
    n = int(duration / h) + 1
    t = np.arange(n) * h
    periods = [40.0, 17.0, 9.0, 5.0, 2.5, 1.3]
    phases = rng.uniform(0, 2 * np.pi, len(periods))
    command = sum(np.sin(2 * np.pi * t / p + f) for p, f in zip(periods, phases))
    command *= np.deg2rad(15.0) / np.std(command)
    a1, a0, b = TRUTH["a1"], TRUTH["a0"], TRUTH["b"]
    x = np.zeros(3)  # psi, eta1, eta2
    delta = 0.0
    psi = np.empty(n)
    rudder = np.empty(n)
    for k in range(n):
        psi[k], rudder[k] = x[0], delta

        def f(x, d):
            return np.array([x[1] + T3 * x[2], x[2], b * d - a0 * x[1] - a1 * x[2]])

        k1 = f(x, delta)
        k2 = f(x + h / 2 * k1, delta)
        k3 = f(x + h / 2 * k2, delta)
        k4 = f(x + h * k3, delta)
        x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        x[2] += np.sqrt(q * h) * rng.standard_normal()  # yaw-moment gust on eta2's equation
        delta += h * (command[k] - delta) / 1.0  # 1 s servo
    step = int(round(1 / (rate * h)))
    keep = np.arange(0, n, step)
    z = ar_sd * rng.standard_normal()
    a = np.exp(-1 / (rate * tau))
    sensor = np.empty(len(keep))
    for i in range(len(keep)):
        sensor[i] = z
        z = a * z + ar_sd * np.sqrt(1 - a * a) * rng.standard_normal()
    logged = psi[keep] + sensor + white * rng.standard_normal(len(keep))
    return t[keep], rudder[keep], logged


def config(noise):
    lines = [
        "model: {family: nomoto, type: second_order_rates}",
        "experiments:",
        "  - {name: run, file: data.csv, inputs: {delta: delta}, outputs: {psi: psi}}",
        "stages:",
        "  - name: fit",
        "    parameters:",
    ]
    for name in NAMES:
        lines.append(f"      {name}: {{start: {TRUTH[name] * 1.3:.10g}}}")
    if noise:
        lines.append(f"    noise: {noise}")
    return "\n".join(lines) + "\n"


def child_cpu(command, cwd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    result = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return result, cpu


def engine(binary, folder, noise):
    with open(os.path.join(folder, "config.yaml"), "w") as f:
        f.write(config(noise))
    out = os.path.join(folder, "out")
    shutil.rmtree(out, ignore_errors=True)
    result, cpu = child_cpu([binary, "run", "config.yaml", "--out", "out", "--quiet",
                             "--no-report"], folder)
    if result.returncode not in (0, 3, 4):
        raise RuntimeError(result.stderr)
    with open(os.path.join(out, "results.json")) as f:
        results = json.load(f)
    estimates = {e["name"]: (e["value"], e["std_error"]) for e in results["stages"][-1]["estimates"]}
    return {n: estimates[n] for n in NAMES}, cpu, results["verdict"]


def peer(folder):
    start = ",".join(f"{TRUTH[n] * 1.3:.10g}" for n in NAMES)
    result, cpu = child_cpu([sys.executable, os.path.join(HERE, "peer_filter_error.py"), "--csv",
                             "data.csv", "--time", "t", "--input", "delta", "--output", "psi",
                             "--ar1", "--start", start, "--json", "peer.json"], folder)
    with open(os.path.join(folder, "peer.json")) as f:
        fit = json.load(f)
    if result.returncode != 0 or "estimates" not in fit:
        # The peer's own refusal (e.g. no innovation variance consistent with its start).
        return None, cpu, "failed: " + fit.get("error", result.stderr[-200:])
    converged = "converged" if fit.get("converged") else "not converged"
    return {n: (fit["estimates"][n], fit["std_errors"][n] or float("nan")) for n in NAMES}, cpu, \
        converged


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--binary", default=os.path.join(HERE, "..", "..", "build", "vesselid"))
    parser.add_argument("--no-peer", action="store_true")
    args = parser.parse_args()
    binary = os.path.abspath(args.binary)
    rows = {"oe": [], "fe": [], "peer": []}
    with tempfile.TemporaryDirectory() as folder:
        for seed in range(1, args.seeds + 1):
            t, delta, psi = simulate(seed)
            np.savetxt(os.path.join(folder, "data.csv"), np.column_stack([t, delta, psi]),
                       delimiter=",", header="t,delta,psi", comments="", fmt="%.10g")
            fits = {
                "oe": engine(binary, folder, ""),
                "fe": engine(binary, folder,
                             "{method: filter_error, measurement: {psi: {type: ar1, white: true}},"
                             " process: {eta2: auto}}"),
            }
            if not args.no_peer:
                fits["peer"] = peer(folder)
            for method, (estimates, cpu, verdict) in fits.items():
                if estimates is None:
                    rows[method].append((cpu, [float("nan")] * len(NAMES), verdict, None))
                    print(f"seed {seed} {method:4s} cpu {cpu:6.2f} s {verdict}")
                    continue
                z = [(estimates[n][0] - TRUTH[n]) / estimates[n][1] for n in NAMES]
                rows[method].append((cpu, z, verdict, estimates))
                print(f"seed {seed} {method:4s} cpu {cpu:6.2f} s verdict {verdict:9s} " +
                      " ".join(f"{n} {estimates[n][0]:.5g} (SE {estimates[n][1]:.2g}, "
                               f"z {zz:+.1f})" for n, zz in zip(NAMES, z)))
    print("\nmethod  median CPU s  |z| RMS   inside 95 % (all parameters)  verdicts")
    for method, data in rows.items():
        if not data:
            continue
        cpu = np.median([d[0] for d in data])
        z = np.array([d[1] for d in data if d[3] is not None])
        if len(z) == 0:
            z = np.full((1, len(NAMES)), np.nan)
        inside = np.mean(np.abs(z) < 1.96)
        verdicts = {}
        for d in data:
            verdict = d[2].split(":")[0]
            verdicts[verdict] = verdicts.get(verdict, 0) + 1
        print(f"{method:6s}  {cpu:12.2f}  {np.sqrt(np.mean(z ** 2)):7.2f}   {100 * inside:5.0f} %"
              f"                      {verdicts}")


if __name__ == "__main__":
    main()
