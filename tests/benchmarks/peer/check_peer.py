#!/usr/bin/env python3
"""Keeps the SciPy peer (nomoto_peer.py) honest; ctest runs it as `peer_check`.

  check_peer.py --vesselid build/vesselid --work build/peer_check

1. Truth: `vesselid simulate` makes 150 s of the patrol vessel's heading-controlled sine
   (peer_check.yaml: closed loop with steering gear, cubic rudder interpolation); the peer,
   from 20 % off every parameter, must recover T1, T2, T3, K within 0.01 %.
2. Agreement with the engine on data of another model: the tanker's zigzags
   (configs/nomoto_tanker.yaml: Norrbin with a rudder-rate limit, yaw disturbance, heading
   quantised, degrees, 1 Hz) fitted by a first-order model with a rudder bias per run and free
   initial psi and r (tanker4_first_order.yaml): the peer and `vesselid run` must reach the
   same cost (1e-6 relative) and estimates (1e-4 relative).
3. The second-order fit of the same zigzags (tanker4_second_order.yaml), far from its optimum
   (T1 5x off, rudder biases 0): a pole-zero cancellation (T2 = T3) lies between, and the
   optimum has T2 on its bound. The engine must reach the peer's cost (1e-3 relative; it once
   stopped at 2.3x, on the ridge, and then at 1.10x, its projected steps stalled with T2 on
   the bound).

Exit 0 when all hold; otherwise the differences on stderr and exit 1.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", ".."))


def run(command, env=None):
    done = subprocess.run(command, capture_output=True, text=True, env=env)
    if done.returncode != 0:
        sys.exit("%s failed (exit %d):\n%s" % (" ".join(command), done.returncode,
                                               done.stderr[-3000:]))
    return done.stdout


def agree(label, config, data, args, peer, env):
    """The peer and `vesselid run` on one config: equal cost and estimates."""
    failures = []
    out = os.path.join(args.work, os.path.splitext(os.path.basename(config))[0])
    run([args.vesselid, "run", config, "--data", data, "--out", out, "--quiet"])
    with open(os.path.join(out, "results.json")) as f:
        stage = json.load(f)["stages"][0]
    engine = {e["name"]: e["value"] for e in stage["estimates"] if e["kind"] == "parameter"}
    solve = json.loads(run(peer + [config, "--data", data], env))["solves"][0]
    mine = dict(solve["estimates"])
    names = ["zz10s_a", "zz10p_a", "zz20s_a", "zz20p_a"]
    mine.update({"delta_0[%s]" % n: v for n, v in zip(names, solve["per_experiment"]["delta_0"])})
    print("tanker, 4 zigzags, first order, %s: engine cost %.10g, peer %.10g" %
          (label, stage["cost"], solve["cost"]))
    if not abs(stage["cost"] - solve["cost"]) <= 1e-6 * stage["cost"]:
        failures.append("tanker (%s): cost %.10g (engine) vs %.10g (peer)" %
                        (label, stage["cost"], solve["cost"]))
    for name, value in mine.items():
        if name not in engine:
            failures.append("tanker (%s): the engine reports no %s" % (label, name))
        elif not abs(engine[name] - value) <= 1e-4 * abs(engine[name]):
            failures.append("tanker (%s): %s = %.8g (engine) vs %.8g (peer)" %
                            (label, name, engine[name], value))
    return failures


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--vesselid", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    # A fresh work folder: vesselid writes only into empty folders or its own earlier output.
    for folder in os.listdir(args.work) if os.path.isdir(args.work) else []:
        if folder != "numba_cache":
            shutil.rmtree(os.path.join(args.work, folder), ignore_errors=True)
    env = dict(os.environ, NUMBA_CACHE_DIR=os.path.join(args.work, "numba_cache"))
    peer = [sys.executable, os.path.join(HERE, "nomoto_peer.py")]
    failures = []

    config = os.path.join(HERE, "peer_check.yaml")
    data = os.path.join(args.work, "patrol_short")
    run([args.vesselid, "simulate", config, "--out", data])
    result = json.loads(run(peer + [config, "--data", data], env))
    truth = {"T1": 2.0875, "T2": 0.3179, "T3": 0.1830, "K": -0.1724}
    estimates = result["solves"][0]["estimates"]
    print("peer (%s) on the patrol sine: %s" % (result["backend"], estimates))
    for name, value in truth.items():
        if not abs(estimates[name] - value) <= 1e-4 * abs(value):
            failures.append("patrol sine: %s = %.8g, truth %.8g" % (name, estimates[name], value))

    tanker = os.path.join(args.work, "tanker")
    run([args.vesselid, "simulate", os.path.join(ROOT, "configs", "nomoto_tanker.yaml"),
         "--out", tanker])
    shipped = os.path.join(HERE, "tanker4_first_order.yaml")
    with open(shipped) as f:
        variant = yaml.safe_load(f)
    variant["stages"][0]["integration"] = {"max_step": 0.3}  # 4 RK4 steps per 1 s sample
    variant["experiment_defaults"]["interpolation"] = {"delta": "zero_order_hold"}
    held = os.path.join(args.work, "tanker4_first_order_zoh.yaml")
    with open(held, "w") as f:
        yaml.safe_dump(variant, f, sort_keys=False)
    for label, config in (("linear input, 1 s steps", shipped),
                          ("held input, 0.3 s steps", held)):
        failures += agree(label, config, tanker, args, peer, env)

    second = os.path.join(HERE, "tanker4_second_order.yaml")
    out = os.path.join(args.work, "tanker4_second_order")
    run([args.vesselid, "run", second, "--data", tanker, "--out", out, "--quiet", "--no-report"])
    with open(os.path.join(out, "results.json")) as f:
        engine_cost = json.load(f)["stages"][0]["cost"]
    peer_cost = json.loads(run(peer + [second, "--data", tanker], env))["solves"][0]["cost"]
    print("tanker, 4 zigzags, second order: engine cost %.6g, peer %.6g" % (engine_cost, peer_cost))
    # Measured 1.0000000x (0.000875095618 both) since a solve that ends with unknowns on a
    # bound continues with them held there (engine/solve/local_solve.cc); 1.10x before.
    if not engine_cost <= 1.001 * peer_cost:
        failures.append("tanker, second order: cost %.6g (engine) is %.2fx the peer's %.6g" %
                        (engine_cost, engine_cost / peer_cost, peer_cost))
    for failure in failures:
        print("FAIL " + failure, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
