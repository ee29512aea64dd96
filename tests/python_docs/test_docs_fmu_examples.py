"""The docs' fmpy examples run as written, against an FMU exported from a run of the shipped
tanker config, with the project's own FMI master following fmpy's conventions
(tests/support/fmi_master: start values in modelDescription order, inputs interpolated at each
communication point)."""
import os
import pathlib
import re
import subprocess
import sys

import numpy as np
import pytest

SOURCE = pathlib.Path(os.environ["VESSELID_SOURCE_DIR"])
BINARY = os.environ["VESSELID_BINARY"]
sys.path.insert(0, str(SOURCE / "tests" / "support" / "fmi_master"))

from fmpy import simulate_fmu  # noqa: E402  (the project's master, see above)

FMU = "out/export/nomoto_norrbin_n1_speed.fmu"


def fmpy_examples():
    examples = []
    for doc in sorted((SOURCE / "docs").glob("*.md")):
        for block in re.findall(r"```python\n(.*?)```", doc.read_text(), re.S):
            if "fmpy" in block:
                examples.append(pytest.param(block, id=doc.name))
    return examples


@pytest.fixture(scope="module")
def run_folder(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fmu_docs")
    config = str(SOURCE / "configs" / "nomoto_tanker.yaml")
    for args in (["simulate", config, "--out", "data"],
                 ["run", config, "--data", "data", "--out", "out", "--quiet"],
                 ["export", "out", "--format", "fmu"]):
        subprocess.run([BINARY, *args], cwd=folder, check=True, capture_output=True)
    return folder


@pytest.mark.parametrize("code", fmpy_examples())
def test_docs_example_runs_as_written(code, run_folder, monkeypatch):
    monkeypatch.chdir(run_folder)
    names = {}
    exec(compile(code, "docs example", "exec"), names)
    result = names["result"]
    assert len(result) == 600
    assert np.all(np.isfinite(result["psi"]))
    # The draws spread the heading: not all members fly the same.
    assert np.max(names["spread"]) > 0.0


def test_a_parameter_set_beside_ensemble_member_is_kept(run_folder, monkeypatch):
    monkeypatch.chdir(run_folder)
    t = np.arange(0.0, 301.0, 1.0)
    signals = np.array(list(zip(t, np.zeros_like(t), np.full_like(t, 7.7))),
                       dtype=[("time", float), ("delta", float), ("U", float)])
    fly = lambda start: simulate_fmu(FMU, start_time=0.0, stop_time=300.0, output_interval=1.0,
                                     input=signals, start_values=start,
                                     output=["psi", "delta_0"])
    member = fly({"ensemble_member": 7})
    offset = fly({"ensemble_member": 7, "delta_0": 0.02})
    assert np.all(offset["delta_0"] == 0.02)
    assert abs(offset["psi"][-1] - member["psi"][-1]) > np.deg2rad(1.0)


def test_a_missing_start_variable_is_named(run_folder, monkeypatch):
    monkeypatch.chdir(run_folder)
    with pytest.raises(Exception, match="could not be set: initial_u"):
        simulate_fmu(FMU, start_time=0.0, stop_time=10.0, output_interval=1.0,
                     start_values={"initial_u": 7.7})
