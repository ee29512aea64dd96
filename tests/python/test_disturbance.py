"""A filter-error stage from Python: the disturbance it identified is a typed object of the
stage (StageResult.disturbance: the model in words, auto's candidates, the held-out predictions
through the filter), the identified model carries the process noise (IdentifiedModel.
process_noise) and `predict` flies it; an output-error stage has none. The patrol vessel's
multi-sine record with 0.1 deg of rudder noise (output error's residuals coloured by the
rudder's noise integrated), as tests/system/filter_error_run_test.cc runs it from the CLI; and
a gusty ship simulated here, where auto chooses a filter after output error's outlier screen."""
import json
import math
import os
import subprocess

import numpy as np
import pandas as pd
import pytest
import yaml

import vesselid

CONFIG = {
    "model": {"family": "nomoto", "type": "second_order"},
    "simulation": {
        "truth": {"T1": 2.0875, "T2": 0.3179, "T3": 0.1830, "K": -0.1724},
        "steering_gear": {"Tm": 1.0, "kp": 0.7, "rudder_limit_deg": 35},
        "sample_time": 0.1,
        "experiments": [
            {"file": name + ".csv", "duration": duration, "seed": seed,
             "excitation": {"type": "multisine", "amplitude_deg": 20,
                            "periods": [60, 30, 15, 7.5, 4]},
             "noise": {"rudder_deg": 0.1, "heading_deg": 0.1}}
            for name, duration, seed in (("multisine", 600, 12), ("check", 120, 13))]},
    "experiments": [{"name": name, "file": name + ".csv", "inputs": {"delta": "delta"},
                     "outputs": {"psi": "psi"}} for name in ("multisine", "check")],
    "stages": [{
        "name": "multisine", "experiments": ["multisine"], "validation": ["check"],
        "parameters": {"T1": {"start": 2.5, "lower": 0.01, "upper": 20.0},
                       "T2": {"start": 0.26, "lower": 0.01, "upper": 20.0},
                       "T3": {"start": 0.22, "lower": 0.0, "upper": 5.0},
                       "K": {"start": -0.2, "lower": -2.0, "upper": -0.001}},
        "noise": {"method": "auto"}}],
}


@pytest.fixture(scope="module")
def records():
    return vesselid.simulate(CONFIG)


def config_without_simulation(noise):
    config = {k: v for k, v in CONFIG.items() if k != "simulation"}
    config["stages"] = [dict(CONFIG["stages"][0])]
    if noise is None:
        config["stages"][0].pop("noise")
    else:
        config["stages"][0]["noise"] = noise
    return config


def test_the_stage_names_its_disturbance_and_the_model_carries_the_gusts(records):
    result = vesselid.run(config_without_simulation(
        {"method": "filter_error", "process": {"xi2": "auto"},
         "measurement": {"psi": {"type": "white"}}}), data=records)
    stage = result.stages[0]
    d = stage.disturbance
    assert isinstance(d, vesselid.Disturbance)
    assert d.method == "filter_error"
    assert "process noise on xi2" in d.model
    assert math.isfinite(d.negative_log_likelihood)
    assert d.candidates.empty  # auto's only
    p = d.predictions
    assert list(p["experiment"]) == ["check"] and list(p["output"]) == ["psi"]
    assert p["one_step_fit_percent"][0] >= p["free_run_fit_percent"][0]
    # The same numbers results.json gives.
    written = result.json["stages"][0]["disturbance"]
    assert written["negative_log_likelihood"] == pytest.approx(d.negative_log_likelihood)
    # The identified model carries the process noise the stage estimated, and predict flies it.
    q = stage.estimates.loc["q.process.xi2"]
    assert q["kind"] == "noise"
    noise = result.model.process_noise
    assert list(noise.index) == ["xi2"]
    assert noise.loc["xi2", "spectral_density"] == pytest.approx(q["value"])
    predicted = vesselid.predict(result, length=30, speed=6, members=20)
    assert [n["state"] for n in predicted["process_noise"]] == ["xi2"]
    assert all(f["disturbance_members"] == 20 for f in predicted["figures"])
    assert "with disturbance" in predicted["text"]


def test_auto_lists_its_candidates(records):
    result = vesselid.run(config_without_simulation({"method": "auto"}), data=records)
    d = result.stages[0].disturbance
    assert d is not None and d.method == "auto"
    c = d.candidates
    assert c.index[0] == "output_error"
    assert c["chosen"].sum() == 1
    assert c.loc[c["chosen"], "bic"].iloc[0] == c.loc[c["solved"], "bic"].min()


def test_output_error_has_no_disturbance(records):
    result = vesselid.run(config_without_simulation(None), data=records)
    assert result.stages[0].disturbance is None
    assert result.model.process_noise.empty
    assert "disturbance_interval" not in vesselid.predict(result, members=5)["figures"][0]


def test_predict_refuses_what_the_cli_refuses(records):
    result = vesselid.run(config_without_simulation(None), data=records)
    with pytest.raises(ValueError, match="speed nan: not a number"):
        vesselid.predict(result, speed=float("nan"), members=5)
    with pytest.raises(ValueError, match="seed -1: a whole number >= 0"):
        vesselid.predict(result, seed=-1, members=5)


def _gusty_record(path, seed, period, rate_hz, bias_deg, psi0):
    """A first-order ship (T 8 s, K 0.12 1/s) under yaw-rate gusts, simulated here (RK4 at
    0.01 s), its heading logged with AR(1) (3 s, 0.3 deg) and white noise: CSV time, delta, psi."""
    rng = np.random.default_rng(seed)
    h, T, K = 0.01, 8.0, 0.12
    t = np.arange(int(600 / h) + 1) * h
    amp = np.radians(15)
    delta = (amp * np.sin(2 * np.pi * t / period) + 0.5 * amp * np.sin(6.6 * np.pi * t / period + 1)
             + np.radians(bias_deg))
    gust = np.sqrt(2e-7 * h) * rng.standard_normal(len(t))
    psi = np.empty(len(t))
    psi[0], r = psi0, 0.0
    for i in range(len(t) - 1):
        d0, d1 = delta[i], 0.5 * (delta[i] + delta[i + 1])
        k1 = (K * d0 - r) / T
        k2 = (K * d1 - (r + h / 2 * k1)) / T
        k3 = (K * d1 - (r + h / 2 * k2)) / T
        k4 = (K * delta[i + 1] - (r + h * k3)) / T
        psi[i + 1] = psi[i] + h / 6 * (6 * r + h * (k1 + k2 + k3))  # RK4 of psi' = r
        r += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4) + gust[i]
    keep = np.arange(0, len(t), int(round(1 / (rate_hz * h))))
    a = np.exp(-1 / rate_hz / 3.0)
    sensor = np.empty(len(keep))
    sensor[0] = np.radians(0.3) * rng.standard_normal()
    for i in range(1, len(keep)):
        sensor[i] = a * sensor[i - 1] + np.radians(0.3) * np.sqrt(1 - a * a) * rng.standard_normal()
    pd.DataFrame({"time": t[keep],
                  "delta": delta[keep] + np.radians(0.05) * rng.standard_normal(len(keep)),
                  "psi": psi[keep] + sensor + np.radians(0.05) * rng.standard_normal(len(keep))}
                 ).to_csv(path, index=False, float_format="%.8f")


def test_output_errors_outlier_screen_says_whose_fit_it_judged(tmp_path):
    # Three records of a gusty ship; output error's outlier screen flags one of them. When auto
    # then chooses a filter, the screen's finding names output error's fit: its numbers (the
    # record's RMS cost, an initial state) are not the chosen model's.
    for i, (period, rate, bias, psi0) in enumerate([(60, 5, 0.5, 0.0), (45, 5, -0.7, 0.3),
                                                     (80, 2, 1.0, -0.2)]):
        _gusty_record(tmp_path / ("run%d.csv" % (i + 1)), i + 1, period, rate, bias, psi0)
    config = {
        "model": {"family": "nomoto", "type": "first_order"},
        "experiment_defaults": {"time": {"column": "time"}, "inputs": {"delta": "delta"},
                                "outputs": {"psi": "psi"}},
        "experiments": [{"name": "run%d" % i, "file": "run%d.csv" % i} for i in (1, 2, 3)],
        "stages": [{"name": "s1", "free_initial_states": ["psi", "r"], "noise": "auto",
                    "parameters": {"T": {"start": 5.0, "lower": 0.5, "upper": 50},
                                   "K": {"start": 0.08, "lower": 0.001, "upper": 1},
                                   "delta_0": {"start": 0.0, "lower": -0.1, "upper": 0.1,
                                               "role": "per_experiment"}}}]}
    path = tmp_path / "config.yaml"
    path.write_text(yaml.safe_dump(config))
    out = tmp_path / "out"
    status = subprocess.run([os.environ["VESSELID_BINARY"], "run", str(path), "--data",
                             str(tmp_path), "--out", str(out), "--quiet", "--no-report"],
                            capture_output=True, text=True)
    assert status.returncode == 0, status.stderr
    stage = json.loads((out / "results.json").read_text())["stages"][0]
    chosen = [c["name"] for c in stage["disturbance"]["candidates"] if c["chosen"]]
    assert chosen and chosen[0] != "output_error", stage["disturbance"]
    outliers = [f for f in stage["findings"] if f["kind"] == "outliers"]
    assert outliers, [f["kind"] for f in stage["findings"]]
    for f in outliers:
        assert f["message"].startswith("in output error's fit, before the disturbance model "
                                       "was chosen: "), f["message"]
