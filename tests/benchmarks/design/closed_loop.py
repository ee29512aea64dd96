#!/usr/bin/env python3
"""The closed-loop check of `vesselid design` (docs/design.md): a shipped design config's run,
its plan, and the plan flown by the project's simulators (with noise and the structure the
model lacks: the steering gear, rudder noise; the catamaran's physics), identified with the
run's records, the achieved standard errors against the predicted ones and against the
alternatives'.

    python3 tests/benchmarks/design/closed_loop.py [--seeds 20] [--work DIR] [config ...]

Imported by tests/python/test_design.py and tests/python_long/test_design_closed_loop.py.
"""
import argparse
import copy
import json
import os
import statistics
import subprocess
import sys
import tempfile

import yaml

SOURCE = os.environ.get("VESSELID_SOURCE_DIR",
                        os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..")))
BINARY = os.environ.get("VESSELID_BINARY", os.path.join(SOURCE, "build", "vesselid"))


def vesselid(*args):
    """Runs the CLI; its stdout, or an exception with its stderr."""
    done = subprocess.run([BINARY] + [str(a) for a in args], capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError("vesselid %s: %s" % (" ".join(map(str, args)), done.stderr[-3000:]))
    return done.stdout


def plan(config, work, design_extra=None):
    """Simulates, runs and designs `config` (with `design_extra` merged into its design
    section) in `work`: the path of design.json."""
    cfg = yaml.safe_load(open(config))
    if design_extra:
        cfg["design"].update(design_extra)
    path = os.path.join(work, "config.yaml")
    yaml.safe_dump(cfg, open(path, "w"))
    vesselid("simulate", path, "--out", os.path.join(work, "data"))
    vesselid("run", path, "--data", os.path.join(work, "data"), "--out",
             os.path.join(work, "run"), "--quiet", "--no-report")
    vesselid("design", path, "--from", os.path.join(work, "run"), "--quiet")
    return cfg, os.path.join(work, "run", "design", "design.json")


def _final(results, names):
    """The final values and standard errors of `names` (None: undetermined)."""
    found = {p["name"]: p for p in results["parameters"]}
    return {n: (found[n]["value"], found[n]["std_error"]) for n in names}


def nomoto_closed_loop(cfg, work, design_json, kind, seeds):
    """The plan (kind "planned") or a 20/20 zigzag of the plan's duration (kind
    "zigzag_20_20") flown by the closed-loop simulator with the first record's noise, seeds
    1..seeds, each identified with the run's records: {parameter: [(value, se), ...]}."""
    design = json.load(open(design_json))
    names = [p["name"] for p in design["parameters"]]
    first = cfg["simulation"]["experiments"][0]
    achieved = {n: [] for n in names}
    for seed in seeds:
        c = copy.deepcopy(cfg)
        c.pop("design", None)
        new = {"file": "new_%s_%d.csv" % (kind, seed), "duration": design["duration"],
               "noise": first["noise"], "seed": 1000 + seed}
        if kind == "planned":
            new["excitation"] = {"type": "planned",
                                 "file": os.path.join(os.path.dirname(design_json),
                                                      "planned_input.csv")}
        else:
            new["excitation"] = {"type": "zigzag", "rudder_deg": 20, "heading_deg": 20}
        c["simulation"]["experiments"] = [first, new]
        c["experiments"].append({"name": "new", "file": new["file"], "inputs": {"delta": "delta"},
                                 "outputs": {"psi": "psi"}})
        c["stages"][-1]["experiments"] = c["stages"][-1]["experiments"] + ["new"]
        path = os.path.join(work, "%s_%d.yaml" % (kind, seed))
        yaml.safe_dump(c, open(path, "w"))
        vesselid("simulate", path, "--out", os.path.join(work, "loop"))
        out = os.path.join(work, "loop_%s_%d" % (kind, seed))
        vesselid("run", path, "--data", os.path.join(work, "loop"), "--out", out, "--quiet",
                 "--no-report")
        final = _final(json.load(open(os.path.join(out, "results.json"))), names)
        for n in names:
            achieved[n].append(final[n])
    return achieved


def input_gain_closed_loop(cfg, work, design_json, seed=1):
    """The plan flown by the catamaran simulator and identified with the run's campaign:
    {parameter: (value, se)}."""
    design = json.load(open(design_json))
    names = [p["name"] for p in design["parameters"]]
    sim = copy.deepcopy(cfg)
    sim.pop("design")
    for key in ("segments", "duration_min", "forward_only"):
        sim["simulation"].pop(key, None)
    sim["simulation"].update({"file": "planned.csv", "seed": 100 + seed, "planned": {
        "file": os.path.join(os.path.dirname(design_json), "planned_input.csv")}})
    sim["experiment_defaults"]["file"] = "planned.csv"
    sim["experiments"] = [{"name": "planned", "segments": {"column": "segment"}}]
    for stage in sim["stages"]:
        stage["experiments"] = ["planned"]
    path = os.path.join(work, "planned_sim.yaml")
    yaml.safe_dump(sim, open(path, "w"))
    vesselid("simulate", path, "--out", os.path.join(work, "data"))
    run = copy.deepcopy(cfg)
    run.pop("design")
    run["experiments"].append({"name": "planned", "file": "planned.csv",
                               "segments": {"column": "segment"}})
    run["stages"][-1]["experiments"] = run["stages"][-1]["experiments"] + ["planned"]
    path = os.path.join(work, "with_plan.yaml")
    yaml.safe_dump(run, open(path, "w"))
    out = os.path.join(work, "with_plan")
    vesselid("run", path, "--data", os.path.join(work, "data"), "--out", out, "--quiet",
             "--no-report")
    return _final(json.load(open(os.path.join(out, "results.json"))), names)


def summary(design_json, achieved_plan, achieved_zigzag):
    """Per parameter: predicted (at the estimate; and the ensemble's median for a robust
    design), achieved (median reported SE, SD of the estimates) for the plan and the 20/20
    zigzag; and the widest parameter's shrink ratios plan / zigzag, predicted and achieved."""
    d = json.load(open(design_json))
    predicted = d["predicted_std_errors"]
    spread = d.get("predicted_std_error_spread", {})
    widest = d["widest"]["parameter"]
    current = predicted["current"][widest]
    rows = {}
    for n in predicted["current"]:
        plan_se = [se for _, se in achieved_plan[n] if se is not None]
        zig_se = [se for _, se in achieved_zigzag[n] if se is not None]
        rows[n] = {
            "current": predicted["current"][n],
            "planned_predicted": predicted["planned"][n],
            "planned_expected": spread.get("planned", {}).get(n, [None, None, None])[1],
            "planned_achieved": statistics.median(plan_se) if plan_se else None,
            "planned_estimate_sd": statistics.stdev([v for v, _ in achieved_plan[n]])
            if len(achieved_plan[n]) > 1 else None,
            "zigzag_predicted": predicted["alternatives"]["zigzag_20_20"][n],
            "zigzag_achieved": statistics.median(zig_se) if zig_se else None,
        }
    w = rows[widest]
    ratios = {
        "widest": widest,
        "predicted": w["zigzag_predicted"] / w["planned_predicted"],
        "achieved": w["zigzag_achieved"] / w["planned_achieved"],
        "achieved_over_predicted": w["planned_achieved"] / w["planned_predicted"],
        "achieved_over_expected": (w["planned_achieved"] / w["planned_expected"]
                                   if w["planned_expected"] else None),
        "current": current,
    }
    return rows, ratios


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("configs", nargs="*", default=["design_cargo.yaml", "design_patrol.yaml",
                                                       "design_input_gain.yaml"])
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--work", default=None)
    args = parser.parse_args()
    work = args.work or tempfile.mkdtemp(prefix="vesselid_design_")
    for name in args.configs:
        config = os.path.join(SOURCE, "configs", name)
        folder = os.path.join(work, os.path.splitext(name)[0])
        os.makedirs(folder, exist_ok=True)
        extra = {"robust": {"members": 20}} if "patrol" in name else None
        cfg, design_json = plan(config, folder, extra)
        print("==", name, "(robust design over 20 members)" if extra else "")
        if cfg["model"]["family"] == "input_gain":
            final = input_gain_closed_loop(cfg, folder, design_json)
            d = json.load(open(design_json))
            for n in ("k_r1", "k_r2"):
                print("%-6s today %s, predicted %.4g, achieved %.4g +- %s" % (
                    n, d["predicted_std_errors"]["current"][n],
                    d["predicted_std_errors"]["planned"][n], final[n][0], final[n][1]))
            continue
        seeds = range(1, args.seeds + 1)
        rows, ratios = summary(design_json,
                               nomoto_closed_loop(cfg, folder, design_json, "planned", seeds),
                               nomoto_closed_loop(cfg, folder, design_json, "zigzag_20_20", seeds))
        print("%-4s %10s %10s %10s %10s %10s %10s %10s" % (
            "", "today", "plan pred", "plan exp", "plan ach", "plan SD", "z20 pred", "z20 ach"))
        for n, r in rows.items():
            print("%-4s" % n + "".join(" %10.4g" % (v if v is not None else float("nan"))
                                       for v in (r["current"], r["planned_predicted"],
                                                 r["planned_expected"], r["planned_achieved"],
                                                 r["planned_estimate_sd"], r["zigzag_predicted"],
                                                 r["zigzag_achieved"])))
        print(json.dumps(ratios))


if __name__ == "__main__":
    sys.exit(main())
