"""Every shipped config through Python on DataFrames equals `vesselid run` on its files.

For each config in configs/: `vesselid simulate` writes its records (each family's own
simulator: closed-loop steering with disturbances and quantised sensors, the catamaran and
USV campaigns with their thrust laws, the 6-DOF hierarchy's runs), `vesselid run` identifies
from the files, and vesselid.run from the same records read into DataFrames (round-trip
float parsing: the doubles the engine's reader makes of the text) with the config passed as
a dict without `file` keys. results.json must be equal: every estimate, standard error,
cost, fit and finding to the last bit, timings and the config's name apart.
Every output-error stage is held to a few solver iterations in both (QUICK_ITERATIONS): the
equality is a property of the data path (frames against files, shared logs cut into
windows, segments), which every stage, held-out run and finding still exercises; the
shipped campaigns' convergence is tested by the CLI's own tests, which run them whole.
(Label system_long: the campaigns' data and least-squares stages still take a minute.)
"""
import copy
import json
import os
import subprocess
import sys

import pandas as pd
import pytest
import yaml

import vesselid

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "python"))
from results_compare import drop_times  # noqa: E402

SOURCE = os.environ["VESSELID_SOURCE_DIR"]
BINARY = os.environ["VESSELID_BINARY"]
CONFIGS = sorted(f for f in os.listdir(os.path.join(SOURCE, "configs")) if f.endswith(".yaml"))


QUICK_ITERATIONS = 3


def quick(config):
    """The config with every output-error stage held to QUICK_ITERATIONS solver iterations."""
    for stage in config["stages"]:
        if stage.get("type", "output_error") == "output_error":
            local = stage.setdefault("local", {})
            local["max_iterations"] = min(local.get("max_iterations", QUICK_ITERATIONS),
                                          QUICK_ITERATIONS)
    return config


@pytest.mark.parametrize("name", CONFIGS)
def test_shipped_config_from_frames_equals_the_cli(name, tmp_path):
    shipped = os.path.join(SOURCE, "configs", name)
    subprocess.run([BINARY, "simulate", shipped, "--out", str(tmp_path)], check=True,
                   stdout=subprocess.DEVNULL)
    with open(shipped, encoding="utf-8") as f:
        config = quick(yaml.safe_load(f))
    quick_config = tmp_path / name
    with open(quick_config, "w", encoding="utf-8") as f:
        yaml.safe_dump(config, f)
    subprocess.run([BINARY, "run", str(quick_config), "--data", str(tmp_path), "--out",
                    str(tmp_path / "cli"), "--quiet", "--no-report"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(tmp_path / "cli" / "results.json", encoding="utf-8") as f:
        expected = json.load(f)
    frames, read = {}, {}
    shared = (config.get("experiment_defaults") or {}).pop("file", None)
    for experiment in config["experiments"]:
        file = experiment.pop("file", shared)  # runs cut from one log share its frame
        if file not in read:
            read[file] = pd.read_csv(tmp_path / file, float_precision="round_trip")
        frames[experiment["name"]] = read[file]
    if "experiment_defaults" in config and not config["experiment_defaults"]:
        del config["experiment_defaults"]
    result = vesselid.run(copy.deepcopy(config), data=frames)
    assert drop_times(result.json) == drop_times(expected)
