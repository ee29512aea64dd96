#!/usr/bin/env python3
"""The MMG benchmark: vesselid against a SciPy peer on the KVLCC2 campaign.

  /usr/bin/python3 tests/benchmarks/peer/mmg_benchmark.py --build build [--work DIR]
      [--repeats 3] [--json FILE]

Simulates configs/mmg_kvlcc2.yaml's campaign once (`vesselid simulate`), then runs, paired on
the same machine and alternating which goes first, `--repeats` times: the engine (`vesselid
run` of the shipped config, `--no-report`) and the peer (mmg_peer.py: the same stage, model
and data with SciPy's least_squares at its defaults). Prints the medians and the ratios
engine/peer of the whole process's wall time and of the solve (the engine's stage time from
results.json, the peer's least_squares call), and scores both by what a user wants from the
model: each estimate, put into the truth's equations, flies a 35 deg starboard turning circle
from a straight course at n = 10.4 1/s (the rudder stepped, 0.05 s RK4): advance and tactical
diameter against the truth's, and the linear sway and yaw derivatives against the published
values. Writes everything to --json (default <work>/mmg_benchmark.json).
"""
import argparse
import json
import math
import os
import resource
import statistics
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, HERE)
import mmg_peer  # noqa: E402


def timed(command):
    """(wall seconds, cpu seconds of the child) of running `command`."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def turning_circle(p, ship, n=10.4, rudder_deg=35.0, duration=150.0, h=0.05):
    """Advance and tactical diameter (m) of a turn from the straight course at n."""
    # Self-propulsion speed: X = 0 at v = r = 0, delta = 0 (bisection on u).
    def surge(u):
        dx = np.empty(6)
        ok = mmg_peer.rhs(np.array([0, 0, 0, u, 0, 0], dtype=float), 0.0, n, p, ship, dx)
        return dx[3] if ok else float("nan")
    low, high = 1e-3, 20.0
    for _ in range(100):
        mid = 0.5 * (low + high)
        if surge(mid) > 0:
            low = mid
        else:
            high = mid
    steps = int(duration / h)
    t = np.arange(steps + 1) * h
    delta = np.full(steps + 1, math.radians(rudder_deg))
    out = np.empty((steps + 1, 4))
    x0 = np.array([0, 0, 0, 0.5 * (low + high), 0, 0], dtype=float)
    if not mmg_peer.simulate(p, ship, x0, t, delta, np.full(steps + 1, n), out):
        return float("nan"), float("nan")
    psi = out[:, 2]
    def crossing(target, column):
        k = int(np.argmax(psi >= target))
        if psi[k] < target:
            return float("nan")
        w = (target - psi[k - 1]) / (psi[k] - psi[k - 1])
        return out[k - 1, column] + w * (out[k, column] - out[k - 1, column])
    return crossing(math.pi / 2, 0), abs(crossing(math.pi, 1))


def parameter_vector(estimates):
    p = np.array(mmg_peer.KVLCC2)
    for name, value in estimates.items():
        p[mmg_peer.NAMES.index(name)] = value
    p[mmg_peer.NAMES.index("delta_0")] = 0.0
    return p


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--work")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--json")
    args = parser.parse_args()
    work = args.work or os.path.join(args.build, "mmg_benchmark")
    os.makedirs(work, exist_ok=True)
    binary = os.path.join(args.build, "vesselid")
    config = os.path.join(ROOT, "configs", "mmg_kvlcc2.yaml")
    data = os.path.join(work, "data")
    if not os.path.exists(os.path.join(data, "tc35s.csv")):
        subprocess.run([binary, "simulate", config, "--out", data], check=True,
                       stdout=subprocess.DEVNULL)
    runs = {"engine": [], "peer": []}
    engine_results = peer_results = None
    for repeat in range(args.repeats):
        order = ["engine", "peer"] if repeat % 2 == 0 else ["peer", "engine"]
        for who in order:
            if who == "engine":
                out = os.path.join(work, "engine_%d" % repeat)
                wall, cpu = timed([binary, "run", config, "--data", data, "--out", out,
                                   "--quiet", "--no-report"])
                with open(os.path.join(out, "results.json")) as f:
                    engine_results = json.load(f)
                solve = sum(s["time_seconds"] for s in engine_results["stages"])
            else:
                out = os.path.join(work, "peer_%d.json" % repeat)
                wall, cpu = timed([sys.executable, os.path.join(HERE, "mmg_peer.py"), config,
                                   "--data", data, "--json", out])
                with open(out) as f:
                    peer_results = json.load(f)
                solve = peer_results["solve_seconds"]
            runs[who].append({"wall": wall, "cpu": cpu, "solve": solve})
    median = {who: {k: statistics.median(r[k] for r in runs[who]) for k in ("wall", "cpu", "solve")}
              for who in runs}
    ship, stage, _ = mmg_peer.load(config, data)
    free = [name for name, spec in stage["parameters"].items()
            if (spec or {}).get("role", "free") == "free"]
    engine_estimates = {p["name"]: p["value"] for p in engine_results["parameters"]
                        if p["name"] in free}
    estimates = {"truth": {}, "engine": engine_estimates, "peer": peer_results["estimates"]}
    outcome = {}
    truth_circle = turning_circle(parameter_vector({}), ship)
    for who, values in estimates.items():
        advance, diameter = turning_circle(parameter_vector(values), ship)
        outcome[who] = {
            "advance_m": advance, "tactical_diameter_m": diameter,
            "advance_error_percent": 100 * (advance / truth_circle[0] - 1),
            "tactical_diameter_error_percent": 100 * (diameter / truth_circle[1] - 1),
            "linear_derivative_errors_percent": {
                name: 100 * (values.get(name, mmg_peer.KVLCC2[mmg_peer.NAMES.index(name)]) /
                             mmg_peer.KVLCC2[mmg_peer.NAMES.index(name)] - 1)
                for name in ("Y_v", "Y_r", "N_v", "N_r")}}
    print("MMG KVLCC2 campaign, %d repeats, peer backend %s, %s" %
          (args.repeats, peer_results["backend"], peer_results["message"]))
    print("%-8s %9s %9s %9s" % ("", "wall s", "cpu s", "solve s"))
    for who in ("engine", "peer"):
        print("%-8s %9.2f %9.2f %9.2f" % (who, median[who]["wall"], median[who]["cpu"],
                                         median[who]["solve"]))
    print("%-8s %9.3f %9.3f %9.3f" % ("ratio", median["engine"]["wall"] / median["peer"]["wall"],
                                     median["engine"]["cpu"] / median["peer"]["cpu"],
                                     median["engine"]["solve"] / median["peer"]["solve"]))
    print("35 deg turn from the estimate: advance, tactical diameter (error vs truth); "
          "Y_v, Y_r, N_v, N_r error %")
    for who in ("truth", "engine", "peer"):
        o = outcome[who]
        e = o["linear_derivative_errors_percent"]
        print("%-8s %7.2f m (%+5.1f %%) %7.2f m (%+5.1f %%)   %+6.1f %+6.1f %+6.1f %+6.1f" %
              (who, o["advance_m"], o["advance_error_percent"], o["tactical_diameter_m"],
               o["tactical_diameter_error_percent"], e["Y_v"], e["Y_r"], e["N_v"], e["N_r"]))
    report = {"runs": runs, "median": median, "outcome": outcome, "estimates": estimates,
              "peer": {k: v for k, v in peer_results.items() if k != "estimates"}}
    with open(args.json or os.path.join(work, "mmg_benchmark.json"), "w") as f:
        json.dump(report, f, indent=2)


if __name__ == "__main__":
    main()
