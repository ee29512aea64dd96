#!/usr/bin/env python3
"""Paired benchmark of vesselid against its SciPy reference peer (nomoto_peer.py).

  /usr/bin/python3 tests/benchmarks/peer/compare.py --build build [--cases cargo,patrol,...]
      [--repeats 3] [--patrol-starts 40] [--work DIR] [--json FILE]
      [--peer-tolerances ftol,xtol,gtol]

For every case the engine (`vesselid run`) and the peer run on the same data (simulated once by
`vesselid simulate` from the shipped config; the peer never simulates), one after the other,
alternating which goes first, `--repeats` times; the table shows medians:

  process   whole process: wall, user+system CPU, peak RSS (os.wait4 of each child);
            the peer's includes Python's start-up, importing SciPy and numba, reading the CSVs
  solve     engine: the local refinements of the stage (results.json stages[].refinements[]
            .time_seconds, summed; with a global start the global search too); peer: the
            least_squares call (wall)
  stage     engine: the whole stage (stages[].time_seconds: global start, solve, uncertainty,
            metrics), against the peer's solve (which has no uncertainty analysis)

and ratios engine/peer (< 1: the engine is faster). Cases:

  cargo          configs/nomoto_cargo.yaml as shipped: second-order Nomoto, 300 001 samples,
                 noise-free, from 50 % off every parameter, initial state fixed
  cargo_free_psi the same with the initial heading estimated (free_initial_states: [psi])
  cargo_multisine the same vessel, start and length on a noise-free multi-sine (periods 600 to
                 20 s, as nomoto_cargo_noise.yaml): a near start from which both need about
                 as many iterations, so that the cost per iteration decides
  patrol         configs/nomoto_patrol.yaml, noise-free sine: --patrol-starts starts drawn
                 log-uniform in [truth/5, truth*5] (seed 22), each solved locally by the
                 engine (`global:` removed), by the engine with the shipped global start, and
                 by the peer (local); counts the starts whose T1, T2, T3, K are within 1 % of
                 the truth (T1, T2 ordered). The engine runs one process per start, the peer
                 one process for all starts: compare the solve columns, not the process ones
  tanker4_first  four zigzags of configs/nomoto_tanker.yaml's data (tanker4_first_order.yaml):
                 first-order Nomoto, a rudder bias per run, free initial psi and r
  tanker4_second the same runs, second-order Nomoto (tanker4_second_order.yaml)

The tanker's data come from another model (Norrbin with a steering-gear rate limit, yaw
disturbance, quantised heading), so there is no truth: the table gives both costs (the same
definition: 0.5 sum of squared residuals, each run weighted by 1/sqrt(samples)) and the largest
relative difference of the shared estimates.
"""
import argparse
import copy
import datetime
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", ".."))
PEER = os.path.join(HERE, "nomoto_peer.py")
CASES = ["cargo", "cargo_free_psi", "cargo_multisine", "patrol", "tanker4_first",
         "tanker4_second"]


def load(path):
    with open(path) as f:
        return yaml.safe_load(f)


def dump(config, path):
    with open(path, "w") as f:
        yaml.safe_dump(config, f, sort_keys=False)
    return path


def spawn(command, env=None):
    """Runs a command, reaping it with os.wait4 for its own CPU time and peak RSS."""
    start = time.perf_counter()
    with tempfile.TemporaryFile("w+") as err_file:
        child = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=err_file, env=env,
                                 text=True)
        out = child.stdout.read()  # stdout is small (the peer's JSON); stderr goes to a file
        _, status, usage = os.wait4(child.pid, 0)
        child.returncode = os.waitstatus_to_exitcode(status)
        wall = time.perf_counter() - start
        err_file.seek(0)
        err = err_file.read()
    if child.returncode != 0:
        raise SystemExit("%s\nfailed (exit %d):\n%s" % (" ".join(command), child.returncode,
                                                         err[-3000:]))
    return {"wall": wall, "cpu": usage.ru_utime + usage.ru_stime,
            "rss_mb": usage.ru_maxrss / 1024.0, "stdout": out, "stderr": err}


class Bench:
    def __init__(self, args):
        self.vesselid = os.path.abspath(os.path.join(args.build, "vesselid"))
        if not os.access(self.vesselid, os.X_OK):
            raise SystemExit("no vesselid in %s: build it first (cmake --build %s --target "
                             "vesselid)" % (args.build, args.build))
        self.work = os.path.abspath(args.work or os.path.join(args.build, "peer_benchmark"))
        os.makedirs(self.work, exist_ok=True)
        self.env = dict(os.environ, NUMBA_CACHE_DIR=os.path.join(self.work, "numba_cache"))
        self.python = args.python

    def data(self, shipped):
        """The shipped config's experiments, simulated once by the engine."""
        stem = os.path.splitext(os.path.basename(shipped))[0]
        folder = os.path.join(self.work, "data", stem)
        marker = os.path.join(folder, ".complete")
        if not os.path.exists(marker):
            spawn([self.vesselid, "simulate", shipped, "--out", folder])
            open(marker, "w").close()
        return folder

    def engine(self, config, data, tag):
        out = os.path.join(self.work, "runs", tag)
        p = spawn([self.vesselid, "run", config, "--data", data, "--out", out, "--quiet"])
        with open(os.path.join(out, "results.json")) as f:
            results = json.load(f)
        stage = [s for s in results["stages"] if "refinements" in s][-1]
        solve = sum(r["time_seconds"] for r in stage["refinements"])
        glob = stage.get("global_start")
        if glob:
            solve += glob.get("time_seconds", 0.0)
        estimates = {e["name"]: e["value"] for e in stage["estimates"]
                     if e.get("kind") == "parameter" and "[" not in e["name"]}
        return {"wall": p["wall"], "cpu": p["cpu"], "rss_mb": p["rss_mb"], "solve": solve,
                "stage": stage["time_seconds"], "iterations": stage.get("iterations"),
                "cost": stage["cost"], "estimates": estimates,
                "termination": [r["termination"] for r in stage["refinements"]]}

    def peer(self, config, data, starts=None, tag="peer"):
        command = [self.python, PEER, config, "--data", data, "--tolerances",
                   self.peer_tolerances]
        if starts is not None:
            path = os.path.join(self.work, tag + "_starts.json")
            with open(path, "w") as f:
                json.dump(starts, f)
            command += ["--starts", path]
        p = spawn(command, self.env)
        result = json.loads(p["stdout"])
        solves = result["solves"]
        return {"wall": p["wall"], "cpu": p["cpu"], "rss_mb": p["rss_mb"],
                "solve": sum(s["solve_seconds"] for s in solves),
                "solve_cpu": sum(s["solve_cpu_seconds"] for s in solves),
                "setup": result["setup_seconds"], "backend": result["backend"],
                "tolerances": result["tolerances"],
                "evaluations": sum(s["evaluations"] for s in solves),
                "jacobians": sum(s["jacobians"] for s in solves),
                "cost": solves[0]["cost"], "estimates": solves[0]["estimates"],
                "solves": solves}


def within(estimates, truth, tolerance=0.01):
    e = dict(estimates)
    if "T1" in e and "T2" in e and e["T1"] < e["T2"]:  # exchangeable time constants
        e["T1"], e["T2"] = e["T2"], e["T1"]
    return all(abs(e[n] - v) <= tolerance * abs(v) for n, v in truth.items())


def max_relative_difference(a, b):
    return max(abs(a[n] - b[n]) / max(abs(b[n]), 1e-12) for n in a if n in b)


def patrol_starts(truth, count, seed=22):
    rng = np.random.default_rng(seed)
    starts = []
    for _ in range(count):
        starts.append({n: float(v * math.exp(rng.uniform(math.log(0.2), math.log(5.0))))
                       for n, v in truth.items()})
    return starts


def prepare(bench, case):
    """(engine configs, peer config, data, truth, peer starts) for a case."""
    cfg = os.path.join(bench.work, "configs")
    os.makedirs(cfg, exist_ok=True)
    if case in ("cargo", "cargo_free_psi"):
        shipped = os.path.join(ROOT, "configs", "nomoto_cargo.yaml")
        config = load(shipped)
        if case == "cargo_free_psi":
            config["stages"][0]["free_initial_states"] = ["psi"]
        path = dump(config, os.path.join(cfg, case + ".yaml"))
        return [path], path, bench.data(shipped), config["simulation"]["truth"], None
    if case == "cargo_multisine":
        config = load(os.path.join(ROOT, "configs", "nomoto_cargo.yaml"))
        run = config["simulation"]["experiments"][0]
        run.update(file="cargo_multisine.csv",
                   excitation={"type": "multisine", "amplitude_deg": 20,
                               "periods": [600, 300, 150, 75, 40, 20]})
        config["experiments"][0].update(name="multisine", file="cargo_multisine.csv")
        path = dump(config, os.path.join(cfg, case + ".yaml"))
        return [path], path, bench.data(path), config["simulation"]["truth"], None
    if case == "patrol":
        shipped = os.path.join(ROOT, "configs", "nomoto_patrol.yaml")
        config = load(shipped)
        config.pop("study", None)
        truth = config["simulation"]["truth"]
        starts = patrol_starts(truth, bench.patrol_count)
        local = copy.deepcopy(config)
        local["stages"][0].pop("global", None)
        peer = dump(local, os.path.join(cfg, "patrol_local.yaml"))
        engine = {"local": [], "global": []}
        for k, start in enumerate(starts):
            for mode, base in (("local", local), ("global", config)):
                c = copy.deepcopy(base)
                for n, v in start.items():
                    c["stages"][0]["parameters"][n]["start"] = v
                path = os.path.join(cfg, "patrol_%s_%02d.yaml" % (mode, k))
                engine[mode].append(dump(c, path))
        return engine, peer, bench.data(shipped), truth, starts
    if case in ("tanker4_first", "tanker4_second"):
        shipped = os.path.join(ROOT, "configs", "nomoto_tanker.yaml")
        name = "tanker4_first_order.yaml" if case == "tanker4_first" else \
            "tanker4_second_order.yaml"
        path = os.path.join(HERE, name)
        return [path], path, bench.data(shipped), None, None
    raise SystemExit("unknown case '%s' (%s)" % (case, ", ".join(CASES)))


def run_case(bench, case, repeats):
    engine_configs, peer_config, data, truth, starts = prepare(bench, case)
    rows = []
    for r in range(repeats):
        order = ("engine", "peer") if r % 2 == 0 else ("peer", "engine")
        row = {}
        for who in order:
            if who == "peer":
                row["peer"] = bench.peer(peer_config, data, starts, tag=case)
            elif case != "patrol":
                row["engine"] = bench.engine(engine_configs[0], data, "%s_%d" % (case, r))
            else:  # one process per start, local and with the global start
                for mode in ("local", "global"):
                    runs = [bench.engine(c, data, "patrol_%s_%d_%02d" % (mode, r, k))
                            for k, c in enumerate(engine_configs[mode])]
                    row["engine_" + mode] = {
                        key: sum(x[key] for x in runs) for key in ("wall", "cpu", "solve",
                                                                   "stage")}
                    row["engine_" + mode]["rss_mb"] = max(x["rss_mb"] for x in runs)
                    row["engine_" + mode]["success"] = sum(within(x["estimates"], truth)
                                                           for x in runs)
                    row["engine_" + mode]["iterations"] = sum(x["iterations"] for x in runs)
        if case == "patrol":
            row["peer"]["success"] = sum(within(s["estimates"], truth)
                                         for s in row["peer"]["solves"])
        rows.append(row)
        print("  %s repeat %d/%d done" % (case, r + 1, repeats), file=sys.stderr)
    return summarise(case, rows, truth)


def median(rows, who, key):
    values = [row[who][key] for row in rows if key in row[who]]
    return statistics.median(values) if values else None


def summarise(case, rows, truth):
    keys = ("wall", "cpu", "rss_mb", "solve", "stage")
    out = {"case": case, "repeats": len(rows), "runs": rows}
    for who in rows[0]:
        out[who] = {k: median(rows, who, k) for k in keys + ("solve_cpu", "setup")
                    if median(rows, who, k) is not None}
    peer = rows[-1]["peer"]
    out["peer"].update(backend=peer["backend"], evaluations=peer["evaluations"],
                       jacobians=peer["jacobians"])
    if case == "patrol":
        out["starts"] = len(peer["solves"])
        for who in rows[0]:
            out[who]["success"] = rows[-1][who]["success"]
        out["engine_local"]["iterations"] = rows[-1]["engine_local"]["iterations"]
    else:
        eng = rows[-1]["engine"]
        out["engine"].update(iterations=eng["iterations"], cost=eng["cost"],
                             termination=eng["termination"], estimates=eng["estimates"])
        out["peer"].update(cost=peer["cost"], estimates=peer["estimates"],
                           termination=peer["solves"][0]["message"])
        out["estimate_difference"] = max_relative_difference(peer["estimates"], eng["estimates"])
        if truth:
            out["engine"]["recovered"] = within(eng["estimates"], truth)
            out["peer"]["recovered"] = within(peer["estimates"], truth)
    engines = [w for w in out if w.startswith("engine") and isinstance(out[w], dict)]
    out["ratios"] = {}
    for who in engines:
        e, p = out[who], out["peer"]
        out["ratios"][who] = {k: e[k] / p[k] for k in ("wall", "cpu", "rss_mb", "solve")
                              if e.get(k) and p.get(k)}
        if e.get("stage") and p.get("solve"):
            out["ratios"][who]["stage"] = e["stage"] / p["solve"]
    return out


def table(results):
    head = ("%-22s %7s %7s %7s %7s %7s | %7s %7s %7s %7s | %s" %
            ("case (engine/peer)", "wall", "cpu", "rss", "solve", "stage",
             "e.wall", "p.wall", "e.solve", "p.solve", "outcome"))
    lines = [head, "-" * len(head)]
    for res in results:
        for who in [w for w in res["ratios"]]:
            r, e, p = res["ratios"][who], res[who], res["peer"]
            label = res["case"] + ("" if who == "engine" else " " + who[len("engine_"):])
            if res["case"] == "patrol":
                outcome = "%d/%d vs %d/%d within 1 %%" % (e["success"], res["starts"],
                                                          p["success"], res["starts"])
            elif "recovered" in e:
                outcome = "truth %s/%s, est. diff %.1e" % ("yes" if e["recovered"] else "NO",
                                                           "yes" if p["recovered"] else "NO",
                                                           res["estimate_difference"])
            else:
                outcome = "cost %.4g vs %.4g, est. diff %.1e" % (e["cost"], p["cost"],
                                                                 res["estimate_difference"])
            if res["case"] != "patrol":
                # iterations: the engine's; the peer's Jacobians (one per accepted iteration)
                # and function evaluations (the 2-point Jacobian costs n more each)
                outcome += "; %d it. vs %d jac. + %d ev." % (e["iterations"], p["jacobians"],
                                                               p["evaluations"])
            fmt = lambda d, k: ("%7.2f" % d[k]) if d.get(k) else "%7s" % "-"  # noqa: E731
            lines.append("%-22s %s %s %s %s %s | %s %s %s %s | %s" % (
                label, fmt(r, "wall"), fmt(r, "cpu"), fmt(r, "rss_mb"), fmt(r, "solve"),
                fmt(r, "stage"), fmt(e, "wall"), fmt(p, "wall"), fmt(e, "solve"),
                fmt(p, "solve"), outcome))
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default="build", help="build tree holding vesselid")
    parser.add_argument("--cases", default=",".join(CASES))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--patrol-starts", type=int, default=40)
    parser.add_argument("--work", help="configs, data and runs (default BUILD/peer_benchmark)")
    parser.add_argument("--json", help="the results (default WORK/compare.json)")
    parser.add_argument("--python", default="/usr/bin/python3", help="runs the peer")
    parser.add_argument("--peer-tolerances", default="1e-12,1e-12,1e-14",
                        help="the peer's ftol,xtol,gtol (default: the engine's Ceres "
                        "tolerances; SciPy's own are 1e-8,1e-8,1e-8)")
    args = parser.parse_args()
    bench = Bench(args)
    bench.peer_tolerances = args.peer_tolerances
    bench.patrol_count = args.patrol_starts
    # Untimed warm-up: numba compiles the integrator into its cache once.
    _, peer_config, data, _, _ = prepare(bench, "tanker4_first")
    warm = bench.peer(peer_config, data)
    print("peer backend: %s (%s)" % (warm["backend"], "RK4 JIT-compiled by numba"
                                     if warm["backend"] == "numba" else
                                     "numba not importable: plain Python RK4, slow"),
          file=sys.stderr)
    results = []
    for case in [c.strip() for c in args.cases.split(",") if c.strip()]:
        results.append(run_case(bench, case, args.repeats))
    text = table(results)
    print(text)
    report = {"date": datetime.datetime.utcnow().isoformat() + "Z", "cpus": os.cpu_count(),
              "load_average": os.getloadavg(), "repeats": args.repeats,
              "peer_backend": warm["backend"], "peer_tolerances": warm["tolerances"],
              "table": text.splitlines(), "cases": results}
    path = args.json or os.path.join(bench.work, "compare.json")
    with open(path, "w") as f:
        json.dump(report, f, indent=1)
    print("\nmedians of %d paired repeats; ratios engine/peer (< 1: engine faster); "
          "seconds and MB absolute; written to %s" % (args.repeats, path))


if __name__ == "__main__":
    main()
