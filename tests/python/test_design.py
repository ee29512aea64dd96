"""`vesselid design` end to end, and vesselid.design from Python (docs/design.md): the cargo
ship's second-order Nomoto model from a short noisy 10/10 zigzag; the D-optimal plan of a
20/20 zigzag's duration shrinks the widest interval at least twice as much as the 20/20
zigzag, predicted and achieved (the plan flown by the closed-loop simulator with its steering
gear and rudder noise, 3 seeds here; tests/benchmarks/design/closed_loop.py runs 20), and it
keeps its limits."""
import json
import os
import statistics
import subprocess
import sys

import numpy as np
import pytest

import vesselid

SOURCE = os.environ["VESSELID_SOURCE_DIR"]
sys.path.insert(0, os.path.join(SOURCE, "tests", "benchmarks", "design"))
import closed_loop  # noqa: E402


@pytest.fixture(scope="module")
def cargo(tmp_path_factory):
    work = str(tmp_path_factory.mktemp("design_cargo"))
    cfg, design_json = closed_loop.plan(os.path.join(SOURCE, "configs", "design_cargo.yaml"), work)
    return work, cfg, design_json


def test_design_json_compares_the_plan_with_the_standard_alternatives(cargo):
    work, cfg, design_json = cargo
    d = json.load(open(design_json))
    se = d["predicted_std_errors"]
    assert set(se["current"]) == {"T1", "T2", "T3", "K"}
    assert set(se["alternatives"]) == {"zigzag_10_10", "zigzag_20_20", "spiral", "multisine",
                                       "prbs"}
    for p in se["current"]:
        assert se["planned"][p] < se["current"][p]
    assert d["limits"]["respected"] and d["limits"]["violations"] == []
    widest = d["widest"]["parameter"]
    shrink = d["widest"]["shrink"]
    assert shrink["planned"] >= 2.0 * shrink["zigzag_20_20"]
    # The plan as the logger gets it: t and the rudder in degrees, within +-35 deg and 2.3 deg/s,
    # as long as the 20/20 zigzag.
    plan = np.genfromtxt(os.path.join(work, "run", "design", "planned_input.csv"), delimiter=",",
                         names=True)
    assert plan.dtype.names == ("t", "delta_deg")
    assert np.max(np.abs(plan["delta_deg"])) <= 35.0 + 1e-9
    assert np.max(np.abs(np.diff(plan["delta_deg"]) / np.diff(plan["t"]))) <= 2.3 * (1 + 1e-9)
    assert plan["t"][-1] == pytest.approx(d["duration"])
    assert os.path.exists(os.path.join(work, "run", "design", "report.html"))
    assert widest in ("T2", "T3")


def test_the_plan_flown_achieves_what_was_predicted(cargo):
    work, cfg, design_json = cargo
    seeds = range(1, 4)
    rows, ratios = closed_loop.summary(
        design_json, closed_loop.nomoto_closed_loop(cfg, work, design_json, "planned", seeds),
        closed_loop.nomoto_closed_loop(cfg, work, design_json, "zigzag_20_20", seeds))
    assert ratios["predicted"] >= 2.0, ratios
    assert ratios["achieved"] >= 2.0, ratios
    # The flown plan's rudder carries 0.1 deg of noise: the run's standard errors include it
    # (input_noise_uncertainty.h) and describe the scatter of the estimates over the seeds,
    # where the design's prediction describes the output noise alone.
    assert ratios["achieved_over_predicted"] >= 0.7, ratios
    # Three seeds give each SD to about +-50 %: the median over the four parameters.
    honesty = statistics.median(row["planned_achieved"] / row["planned_estimate_sd"]
                                for row in rows.values())
    assert 0.5 <= honesty <= 2.0, rows


def test_python_design_returns_the_plan(cargo, tmp_path):
    work, cfg, design_json = cargo
    config = dict(cfg)
    result = vesselid.design(config, os.path.join(work, "run"), out=tmp_path / "plan")
    assert result["limits"]["respected"]
    assert list(result["planned"].columns) == ["t", "delta_deg"]
    assert {"psi", "r"} <= set(result["predicted"].columns)
    assert "Predicted standard errors" in result["text"]
    assert (tmp_path / "plan" / "design.json").exists()
    # The run's own folder is refused (its report.html is the run's).
    with pytest.raises(vesselid.RunError, match="own folder"):
        vesselid.design(cfg, os.path.join(work, "run"), out=os.path.join(work, "run"))
    # A bad section names its key.
    config["design"] = dict(config["design"], criterion="F")
    with pytest.raises(vesselid.ConfigError, match="design.criterion"):
        vesselid.design(config, os.path.join(work, "run"))


def test_example_script_plans(tmp_path):
    script = os.path.join(SOURCE, "examples", "python", "plan_next_experiment.py")
    done = subprocess.run(["/usr/bin/python3", script, str(tmp_path)], cwd=SOURCE,
                          capture_output=True, text=True, check=True)
    assert "shrinks" in done.stdout and "delta_deg" in done.stdout, done.stdout
