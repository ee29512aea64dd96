"""A filter-error stage from Python: the disturbance it identified is a typed object of the
stage (StageResult.disturbance: the model in words, auto's candidates, the held-out predictions
through the filter), the identified model carries the process noise (IdentifiedModel.
process_noise) and `predict` flies it; an output-error stage has none. The patrol vessel's
multi-sine record with 0.1 deg of rudder noise (output error's residuals coloured by the
rudder's noise integrated), as tests/system/filter_error_run_test.cc runs it from the CLI."""
import math

import pytest

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
        "noise": {"method": "auto", "process": {"xi2": "auto"}}}],
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
