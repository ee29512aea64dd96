"""The acceptance of `vesselid design` on the patrol vessel and the catamaran
(docs/design.md; tests/benchmarks/design/closed_loop.py prints the figures over 20 seeds):

* patrol vessel, second-order Nomoto from a short noisy 10/10 zigzag, robust D-optimal plan
  (over 20 ensemble members): shrinks the widest interval at least 1.5 times as much as a
  20/20 zigzag of the same duration, predicted and achieved over 8 noise seeds (20 seeds:
  1.95 and 1.65; the 2x this asked before was measured when the simulator's zigzags of a
  K < 0 ship never reversed, its 20/20 "zigzag" a turn), the achieved standard errors within
  0.7-1.4x of the estimates' scatter (the rudder noise included);
* catamaran after a campaign without astern thrust: the astern coefficients undetermined;
  the plan asks for astern thrust, and flown by the catamaran simulator it determines them.
"""
import json
import os
import statistics
import sys

import numpy as np

SOURCE = os.environ["VESSELID_SOURCE_DIR"]
sys.path.insert(0, os.path.join(SOURCE, "tests", "benchmarks", "design"))
import closed_loop  # noqa: E402


def test_patrol_plan_shrinks_the_widest_interval_more_than_the_20_20_zigzag(tmp_path):
    cfg, design_json = closed_loop.plan(os.path.join(SOURCE, "configs", "design_patrol.yaml"),
                                        str(tmp_path), {"robust": {"members": 20}})
    seeds = range(1, 9)
    rows, ratios = closed_loop.summary(
        design_json,
        closed_loop.nomoto_closed_loop(cfg, str(tmp_path), design_json, "planned", seeds),
        closed_loop.nomoto_closed_loop(cfg, str(tmp_path), design_json, "zigzag_20_20", seeds))
    assert ratios["predicted"] >= 1.5, ratios
    assert ratios["achieved"] >= 1.5, ratios
    # The flown plan's rudder noise is in the reported standard errors (input_noise_uncertainty.h),
    # which describe the estimates' scatter over the seeds; the prediction describes the output
    # noise alone and is optimistic by the rudder noise's part (docs/design.md).
    assert ratios["achieved_over_expected"] >= 0.7, ratios
    honesty = statistics.median(row["planned_achieved"] / row["planned_estimate_sd"]
                                for row in rows.values())
    assert 0.7 <= honesty <= 1.4, rows
    assert json.load(open(design_json))["limits"]["respected"]


def test_catamaran_plan_asks_for_astern_and_determines_it(tmp_path):
    cfg, design_json = closed_loop.plan(
        os.path.join(SOURCE, "configs", "design_input_gain.yaml"), str(tmp_path))
    d = json.load(open(design_json))
    assert d["predicted_std_errors"]["current"]["k_r1"] is None  # undetermined today
    assert d["predicted_std_errors"]["planned"]["k_r1"] is not None
    assert d["limits"]["respected"]
    plan = np.genfromtxt(os.path.join(tmp_path, "run", "design", "planned_input.csv"),
                         delimiter=",", names=True)
    assert min(plan["u_L"].min(), plan["u_R"].min()) < -0.5  # astern
    assert np.all(np.abs(plan["u_L"]) <= 1.0) and np.all(np.abs(plan["u_R"]) <= 1.0)
    final = closed_loop.input_gain_closed_loop(cfg, str(tmp_path), design_json)
    for name in ("k_r1", "k_r2"):
        value, se = final[name]
        assert se is not None and np.isfinite(se) and se < 0.5 * max(abs(value), 0.1), final
