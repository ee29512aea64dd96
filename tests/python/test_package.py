"""The Python package against the CLI, on data the identified model did not make.

The shipped tanker campaign (configs/nomoto_tanker.yaml, simulated by `vesselid simulate`: a
Norrbin ship with a rate-limited steering gear, a slow yaw disturbance and a quantised
compass, logged in degrees, with per-run rudder biases) cut to three training runs and one
held-out run. The CSVs are read into DataFrames with round-trip float parsing (the doubles the
engine's reader makes of the same text) and passed to vesselid.run; results.json must equal
`vesselid run`'s on the files, timings and the config's name apart.
"""
import copy
import json
import os
import subprocess

import numpy as np
import pandas as pd
import pytest
import yaml

import vesselid
from results_compare import drop_times, same_to_digits

SOURCE = os.environ["VESSELID_SOURCE_DIR"]
BINARY = os.environ["VESSELID_BINARY"]
TRAINING = ["zz10s_a", "zz20s_a", "zz35p_a"]
HELD_OUT = ["zz20s_b"]


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    folder = tmp_path_factory.mktemp("tanker")
    shipped = os.path.join(SOURCE, "configs", "nomoto_tanker.yaml")
    subprocess.run([BINARY, "simulate", shipped, "--out", str(folder)], check=True,
                   stdout=subprocess.DEVNULL)
    with open(shipped, encoding="utf-8") as f:
        config = yaml.safe_load(f)
    config.pop("simulation")
    config["sets"] = {"training": TRAINING, "held_out": HELD_OUT}
    # Only the runs used: the record checks read every configured experiment.
    config["experiments"] = [e for e in config["experiments"] if e["name"] in TRAINING + HELD_OUT]
    path = folder / "config.yaml"
    path.write_text(yaml.safe_dump(config))
    frames = {name: pd.read_csv(folder / (name + ".csv"), float_precision="round_trip")
              for name in TRAINING + HELD_OUT}
    cli = folder / "cli"
    subprocess.run([BINARY, "run", str(path), "--out", str(cli), "--quiet", "--no-report"],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(cli / "results.json", encoding="utf-8") as f:
        expected = json.load(f)
    return {"folder": folder, "config": config, "path": path, "frames": frames,
            "expected": expected}


def test_frames_give_the_cli_run(campaign):
    config = copy.deepcopy(campaign["config"])
    for experiment in config["experiments"]:
        experiment.pop("file")
    result = vesselid.run(config, data=campaign["frames"])
    assert drop_times(result.json) == drop_times(campaign["expected"])
    assert result.verdict == campaign["expected"]["verdict"]


def test_result_tables(campaign):
    result = vesselid.run(campaign["path"], data=campaign["frames"])
    parameters = result.parameters
    names = [p["name"] for p in campaign["expected"]["parameters"]]
    assert list(parameters.index) == names
    assert {"value", "std_error", "lower", "upper", "role", "unit"} <= set(parameters.columns)
    for p in campaign["expected"]["parameters"]:
        assert parameters.loc[p["name"], "value"] == p["value"]
    assert list(result.stage_table.index) == [s["name"] for s in campaign["expected"]["stages"]]
    assert [s.name for s in result.stages] == list(result.stage_table.index)
    fits = result.fits
    assert set(fits["role"]) >= {"fit", "validation"}
    assert set(fits["experiment"]) >= set(TRAINING + HELD_OUT)
    assert json.loads(result.to_json()) == result.json
    html = result._repr_html_()
    assert result.verdict in html and "<table" in html
    # The rudder bias in the unit the rudder was logged in (degrees), not radians.
    bias = parameters.loc["delta_0"]
    assert bias["unit"] == "rad" and bias["shown_unit"] == "deg"
    assert ("%.6g" % (bias["value"] * bias["shown_scale"])) in html and ">deg<" in html
    for finding in result.findings:
        assert result.find(kind=finding.kind) and finding.severity in ("info", "warning", "failure")


def test_out_writes_the_cli_files(campaign, tmp_path):
    vesselid.run(campaign["path"], data=campaign["frames"], out=tmp_path / "run", report=False)
    with open(tmp_path / "run" / "results.json", encoding="utf-8") as f:
        written = json.load(f)
    assert drop_times(written) == drop_times(campaign["expected"])
    assert (tmp_path / "run" / "report.txt").exists()


def test_traces_are_the_cli_trace_files(campaign):
    """Result.traces holds the CLI's traces/ files as frames: every one, the same columns (in
    degrees where the tanker logs degrees) and numbers (to the 12 digits the files hold)."""
    result = vesselid.run(campaign["path"], data=campaign["frames"], threads=1)
    folder = campaign["folder"] / "cli" / "traces"
    files = sorted(os.listdir(folder))
    assert sorted(name + ".csv"
                  for name in result.traces) == files
    assert any(".validation." in name for name in result.traces)
    for name, frame in result.traces.items():
        written = pd.read_csv(folder / (name + ".csv"), float_precision="round_trip")
        assert list(frame.columns) == list(written.columns)
        assert len(frame) == len(written)
        if len(frame):  # (a least-squares stage's trace holds no samples)
            np.testing.assert_allclose(frame.to_numpy(), written.to_numpy(dtype=float),
                                       rtol=1e-11, atol=1e-10)  # 12 digits written
    # The output-error stage's: the heading measured and simulated, in degrees as logged.
    heading = result.traces["output_error.zz10s_a"]
    assert {"t", "psi_measured [deg]", "psi_simulated [deg]"} <= set(heading.columns)


def test_threads_do_not_change_the_numbers(campaign):
    one = vesselid.run(campaign["path"], data=campaign["frames"], threads=1)
    two = vesselid.run(campaign["path"], data=campaign["frames"], threads=2)
    assert drop_times(two.json) == drop_times(campaign["expected"])
    assert same_to_digits(drop_times(one.json), drop_times(two.json))


def test_numpy_columns_and_a_data_folder(campaign):
    frames = {name: {c: frame[c].to_numpy() for c in frame.columns}
              for name, frame in campaign["frames"].items()}
    from_arrays = vesselid.run(campaign["path"], data=frames)
    from_folder = vesselid.run(campaign["path"], data=campaign["folder"])
    assert drop_times(from_arrays.json) == drop_times(campaign["expected"])
    assert drop_times(from_folder.json) == drop_times(campaign["expected"])


def test_progress_is_called(campaign):
    seen = []
    vesselid.run(campaign["path"], data=campaign["frames"], progress=seen.append)
    assert seen and {"phase", "iteration", "cost"} <= set(seen[0])


def test_errors_carry_the_cli_messages(campaign):
    config = copy.deepcopy(campaign["config"])
    config["stages"][0]["colour"] = "red"
    with pytest.raises(vesselid.ConfigError, match=r"config:\d+: .*colour"):
        vesselid.run(config, data=campaign["frames"])
    frames = dict(campaign["frames"])
    broken = frames["zz10s_a"].copy()
    broken.loc[5, "t"] = broken.loc[4, "t"]
    frames["zz10s_a"] = broken
    with pytest.raises(vesselid.DataError, match="experiment 'zz10s_a' .*row 5: time"):
        vesselid.run(campaign["path"], data=frames)
    with pytest.raises(vesselid.DataError, match="'nowhere', which is not an experiment"):
        vesselid.run(campaign["path"], data={"nowhere": campaign["frames"]["zz10s_a"]})
    config = copy.deepcopy(campaign["config"])
    for experiment in config["experiments"]:
        experiment.pop("file")
    with pytest.raises(vesselid.ConfigError, match="no data given for it"):
        vesselid.run(config, data={"zz10s_a": campaign["frames"]["zz10s_a"]})
    # A complex column loses nothing silently; a dict column of text is named.
    frames = dict(campaign["frames"])
    complex_frame = frames["zz10s_a"].copy()
    complex_frame["psi"] = complex_frame["psi"] + 1j
    frames["zz10s_a"] = complex_frame
    with pytest.raises(vesselid.DataError, match=r"data\['zz10s_a'\] column 'psi': complex"):
        vesselid.run(campaign["path"], data=frames)
    columns = {k: v.to_numpy() for k, v in campaign["frames"]["zz10s_a"].items()}
    columns["delta"] = columns["delta"].astype(str)
    with pytest.raises(vesselid.DataError, match=r"column 'delta': <U\d+ values, not numbers"):
        vesselid.run(campaign["path"], data={"zz10s_a": columns})


def test_load_config_returns_the_schema_as_data(campaign):
    config = vesselid.load_config(campaign["path"])
    assert config["model"]["family"] == "nomoto"
    assert config["sets"]["training"] == TRAINING
    bad = campaign["folder"] / "bad.yaml"
    bad.write_text(campaign["path"].read_text().replace("stages:", "stagez:"))
    with pytest.raises(vesselid.ConfigError, match="bad.yaml"):
        vesselid.load_config(bad)


def test_example_script_runs(campaign):
    script = os.path.join(SOURCE, "examples", "python", "identify_from_frames.py")
    env = dict(os.environ)
    done = subprocess.run(["/usr/bin/python3", script, str(campaign["folder"])], cwd=SOURCE,
                          env=env, capture_output=True, text=True, check=True)
    assert "verdict:" in done.stdout and "fit_percent" in done.stdout, done.stdout


def test_model_simulates_in_the_configs_units(campaign):
    result = vesselid.run(campaign["path"], data=campaign["frames"])
    model = result.model
    assert model.info["inputs"] == ["delta", "U"]
    values = {p["name"]: p["value"] for p in campaign["expected"]["parameters"]}
    for name in model.parameters.index:
        if name in values:
            assert model.parameters[name] == values[name]
    estimated = [n for n in model.covariance.index if n in model.parameters.index]
    assert estimated and all(model.covariance.loc[n, n] > 0 for n in estimated)
    frame = campaign["frames"]["zz20s_b"][["t", "delta", "U"]]
    # Without rudder, from rest at 30 degrees: the heading stays at 30 degrees.
    still = frame.assign(delta=0.0)
    out = model.simulate(still, initial_state={"psi": 30.0}, parameters={"delta_0": 0.0})
    assert list(out.columns) == ["t", "delta", "U", "psi", "r"] + ["x." + s for s in model.info["states"]]
    assert np.array_equal(out["x.psi"], out["psi"])  # the heading state is the heading output
    assert np.allclose(out["psi"], 30.0, atol=1e-9) and np.allclose(out["r"], 0.0, atol=1e-12)
    # The rudder (degrees in and out): a mirrored rudder mirrors the heading (an odd model).
    ahead = model.simulate(frame, parameters={"delta_0": 0.0})
    mirrored = model.simulate(frame.assign(delta=-frame["delta"]), parameters={"delta_0": 0.0})
    assert np.allclose(ahead["delta"], frame["delta"])
    assert np.allclose(ahead["psi"], -mirrored["psi"], atol=1e-9)
    assert np.abs(ahead["psi"]).max() > 5.0  # degrees: a 20 degree zigzag turns the ship
    with pytest.raises(KeyError, match="no parameter 'T9'"):
        model.simulate(frame, parameters={"T9": 1.0})
    with pytest.raises(vesselid.DataError, match="row 3: time"):
        model.simulate(frame.assign(t=[0.0, 1.0, 2.0, 2.0] + list(frame["t"][4:])))


def test_simulate_gives_the_cli_records_as_frames(campaign):
    config = vesselid.load_config(os.path.join(SOURCE, "configs", "nomoto_tanker.yaml"))
    frames = vesselid.simulate(config)
    assert set(frames) >= set(TRAINING + HELD_OUT)
    for name in TRAINING + HELD_OUT:
        pd.testing.assert_frame_equal(frames[name], campaign["frames"][name])


def test_study_on_frames(campaign, tmp_path):
    config = copy.deepcopy(campaign["config"])
    for experiment in config["experiments"]:
        experiment.pop("file")
    config["study"] = {"seed": 1, "starts": {"runs": 2}}
    lines = []
    study = vesselid.study(config, data=campaign["frames"], out=tmp_path / "study",
                           progress=lines.append)
    assert "starts" in study and "Start-point study" in study["text"]
    assert len(lines) >= 2
    with open(tmp_path / "study" / "study.json", encoding="utf-8") as f:
        assert "starts" in json.load(f)


def test_notebook_runs_top_to_bottom(tmp_path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    notebook = nbformat.read(os.path.join(SOURCE, "examples", "python", "identify_nomoto.ipynb"),
                             as_version=4)
    client = nbclient.NotebookClient(notebook, timeout=300, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    outputs = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    html = [o["data"]["text/html"] for o in outputs
            if o.output_type == "execute_result" and "text/html" in o.get("data", {})]
    assert any("verdict" in h for h in html), "the Result's summary is shown"
    assert (tmp_path / "predicted_zigzag.png").exists()
    nbformat.write(notebook, str(tmp_path / "identify_nomoto.executed.ipynb"))


def test_progress_bar(campaign, capsys):
    pytest.importorskip("tqdm")
    vesselid.run(campaign["path"], data=campaign["frames"], progress=True)
    assert "vesselid" in capsys.readouterr().err


INTERRUPTED_RUN = r"""
import sys, time
import vesselid
config = vesselid.load_config(sys.argv[1])
records = vesselid.simulate(config)
data = {e["name"]: records[e.pop("file")[:-4]] for e in config["experiments"]}
config.pop("simulation")
config.pop("study", None)
# A search of 4000 points (the config's 32 take a fraction of a second): the signal lands in it.
config["stages"][0]["global"]["points"] = 4000
print("started", flush=True)
begin = time.time()
try:
    vesselid.run(config, data=data)
except KeyboardInterrupt:
    print("interrupted after %.1f s" % (time.time() - begin), flush=True)
    sys.exit(0)
print("finished after %.1f s" % (time.time() - begin), flush=True)
sys.exit(1)
"""


def test_ctrl_c_stops_a_run(tmp_path):
    # The patrol run with a long global start: Ctrl-C after one second ends the current solve
    # after its iteration and the run after its stage, within a second even while the global
    # start screens its 4000 points (which took 3.5 s to notice it before the screening polled).
    import signal
    import time
    script = tmp_path / "interrupted.py"
    script.write_text(INTERRUPTED_RUN)
    child = subprocess.Popen(["/usr/bin/python3", str(script),
                              os.path.join(SOURCE, "configs", "nomoto_patrol.yaml")],
                             stdout=subprocess.PIPE, text=True)
    assert child.stdout.readline().strip() == "started"
    time.sleep(1.0)
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=120)
    assert child.returncode == 0, out
    assert out.startswith("interrupted after"), out
    assert float(out.split()[2]) < 2.5, out  # the signal came 1 s after the start


def test_export_and_predict_take_the_runs_model_out(campaign, tmp_path):
    """vesselid.export writes the CLI's files (model.json identical to `vesselid export`'s, an
    FMU archive, the C header, source and example); vesselid.predict gives the CLI's predictions; a folder without a run raises."""
    cli = campaign["folder"] / "cli"
    path = vesselid.export(cli, format="json", out=tmp_path / "py")
    subprocess.run([BINARY, "export", str(cli), "--format", "json", "--out",
                    str(tmp_path / "cli")], check=True, stdout=subprocess.DEVNULL)
    name = os.path.basename(path)
    assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / name).read_text()
    model = json.loads((tmp_path / "py" / name).read_text())
    assert model["family"] == "nomoto" and len(model["ensemble"]["members"]) == 100
    fmu = vesselid.export(cli, format="fmu", out=tmp_path / "fmu")
    import zipfile
    with zipfile.ZipFile(fmu) as archive:
        assert {"modelDescription.xml", "resources/model.json",
                "binaries/linux64/vesselid_model.so"} <= set(archive.namelist())
    header = vesselid.export(cli, format="c", out=tmp_path / "c")
    stem = os.path.basename(header)[:-len(".h")]
    assert header.endswith(".h") and (tmp_path / "c" / (stem + ".c")).exists()
    assert (tmp_path / "c" / (stem + "_example.c")).exists()

    # 20 draws, not the default 100: the same numbers either way is what is checked.
    predictions = vesselid.predict(cli, speed=7.7, members=20, out=tmp_path / "predict")
    subprocess.run([BINARY, "predict", str(cli), "--speed", "7.7", "--members", "20", "--out",
                    str(tmp_path / "cli_predict")], check=True, stdout=subprocess.DEVNULL)
    with open(tmp_path / "cli_predict" / "predictions.json", encoding="utf-8") as f:
        expected = json.load(f)
    text = predictions.pop("text")
    assert predictions == expected
    assert "zigzag_10_10.first_overshoot" in text
    assert expected["length"] == 320.0  # the n1 form's own length
    with pytest.raises(vesselid.RunError, match="results.json"):
        vesselid.export(campaign["folder"], format="json", out=tmp_path / "none")

    # From a RunResult in memory: the same model and predictions, no folder read.
    result = vesselid.run(campaign["path"], data=campaign["frames"])
    from_memory = json.loads(open(vesselid.export(result, format="json", out=tmp_path / "mem"),
                                  encoding="utf-8").read())
    assert from_memory.pop("results") == str(campaign["path"])
    model.pop("results")
    assert from_memory == model
    in_memory = vesselid.predict(result, speed=7.7, members=20)
    in_memory.pop("text")
    assert in_memory.pop("results") == str(campaign["path"])
    expected.pop("results")
    assert in_memory == expected
    with pytest.raises(TypeError, match="needs `out`"):
        vesselid.export(result, format="json")


def test_results_are_the_engines_types(campaign):
    """The results are bound classes of the engine's types, not dicts or Python copies."""
    result = vesselid.run(campaign["path"], data=campaign["frames"])
    assert type(result) is vesselid.RunResult and type(result).__module__ == "vesselid._core"
    assert type(result.model) is vesselid.IdentifiedModel
    assert type(result.findings[0]) is vesselid.Finding
    assert all(type(s) is vesselid.StageResult for s in result.stages)
    stage = result.stages[-1]
    assert stage.name == "output_error" and stage.verdict in ("good", "doubtful", "failed")
    written = {e["name"]: e["value"] for e in campaign["expected"]["stages"][-1]["estimates"]}
    assert stage.estimates.loc["n1", "value"] == written["n1"]
    assert list(stage.correlation.index) == list(stage.correlation.columns)
    with pytest.raises(AttributeError):
        result.verdict = "good"  # read-only
    assert vesselid.__version__ == campaign["expected"]["vesselid_version"]
    version = subprocess.run([BINARY, "--version"], capture_output=True, text=True, check=True)
    assert version.stdout.strip() == vesselid.__version__


def test_model_flies_a_record_as_the_run_did(campaign):
    """result.model.simulate on a training record, with the stage's values, from its estimated
    start and with that run's own rudder bias, is the stage's trace of it (the run's step and
    interpolation: nothing given but the record and the values)."""
    result = vesselid.run(campaign["path"], data=campaign["frames"])
    model = result.model
    assert model.max_step == 0.0 and model.interpolation == {"delta": "linear", "U": "linear"}
    assert model.degrees == {"delta", "psi"}
    estimates = result.stages[-1].estimates
    for run in TRAINING:
        start = {s: estimates.loc["x0.%s[%s]" % (s, run), "value"] for s in ("psi", "r")}
        start["psi"] *= 180 / np.pi  # the heading in the unit it was logged in
        values = {p: estimates.loc[p, "value"] for p in ("T_nd", "K_nd", "n1", "n3_nd")}
        values["delta_0"] = estimates.loc["delta_0[%s]" % run, "value"]
        flown = model.simulate(campaign["frames"][run][["t", "delta", "U"]],
                               initial_state=start, parameters=values)
        trace = result.traces["output_error." + run]
        assert len(flown) == len(trace)
        np.testing.assert_allclose(flown["psi"], trace["psi_simulated [deg]"], rtol=0, atol=1e-9)
    # Settings of its own: a finer step and held inputs change the flight.
    coarse = model.simulate(campaign["frames"][run][["t", "delta", "U"]], initial_state=start,
                            parameters=values, max_step=0.25, interpolation="zero_order_hold")
    assert not np.allclose(coarse["psi"], flown["psi"])


def test_select_chooses_and_runs_a_structure(campaign, tmp_path):
    """vesselid.select cross-validates the candidates and runs the chosen one, as `vesselid
    select` does; the CLI's results.json is the same."""
    config = copy.deepcopy(campaign["config"])
    config["select"]["folds"] = "leave_one_run_out"
    config["select"]["candidates"] = config["select"]["candidates"][:2]
    path = campaign["folder"] / "select.yaml"
    path.write_text(yaml.safe_dump(config))
    lines = []
    result = vesselid.select(path, data=campaign["frames"], out=tmp_path / "py", report=False,
                             progress=lambda p: lines.append(p) if p["phase"] == "select" else None)
    assert type(result) is vesselid.RunResult
    chosen = result.selection["chosen"]
    assert chosen in [c["name"] for c in config["select"]["candidates"]]
    # A case per candidate and fold, and one per candidate on every run.
    assert len(lines) == 2 * (len(result.selection["folds"]) + 1)
    subprocess.run([BINARY, "select", str(path), "--out", str(tmp_path / "cli"), "--quiet",
                    "--no-report"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(tmp_path / "cli" / "results.json", encoding="utf-8") as f:
        expected = json.load(f)
    with open(tmp_path / "py" / "results.json", encoding="utf-8") as f:
        written = json.load(f)
    assert drop_times(result.json) == drop_times(expected) == drop_times(written)


def test_misuse_is_named_not_fatal(campaign, tmp_path):
    """What a new user gets wrong is a clear error of the right class, never a dead process."""
    result = vesselid.run(campaign["path"], data=campaign["frames"])
    model = result.model
    frame = campaign["frames"]["zz20s_b"][["t", "delta", "U"]]
    with pytest.raises(vesselid.DataError, match="input 'delta' has no samples"):
        model.simulate(frame.assign(delta=np.nan))
    with pytest.raises(vesselid.DataError, match="max_step"):
        model.simulate(frame, max_step=-1.0)
    with pytest.raises(TypeError, match="state 'psi': a number"):
        model.simulate(frame, initial_state={"psi": "a"})
    with pytest.raises(TypeError, match="DataFrame or a dict of columns"):
        model.simulate([1, 2, 3])
    # Epoch times as datetime64 are seconds, as run() reads them; other columns are not read.
    stamped = frame.assign(t=pd.to_datetime(frame["t"], unit="s"), note="text")
    pd.testing.assert_frame_equal(model.simulate(stamped).drop(columns="t"),
                                  model.simulate(frame).drop(columns="t"))
    with pytest.raises(ValueError, match="no severity 'WARNING'"):
        result.find(severity="WARNING")
    with pytest.raises(ValueError, match="no finding kind 'bogus'"):
        result.find(kind="bogus")
    with pytest.raises(ValueError, match="out: an empty path"):
        vesselid.export(result, format="json", out="")
    # The progress callback's own exception, not an interrupt; a non-callable one up front.
    def fails(p):
        raise ValueError("boom")
    with pytest.raises(ValueError, match="boom"):
        vesselid.run(campaign["path"], data=campaign["frames"], progress=fails)
    with pytest.raises(TypeError, match="progress must be callable"):
        vesselid.run(campaign["path"], data=campaign["frames"], progress=5)
    # select on a config without a select section: a config error, from Python and the CLI.
    config = copy.deepcopy(campaign["config"])
    config.pop("select")
    plain = campaign["folder"] / "no_select.yaml"
    plain.write_text(yaml.safe_dump(config))
    with pytest.raises(vesselid.ConfigError, match="no select section"):
        vesselid.select(plain, data=campaign["frames"])
    cli = subprocess.run([BINARY, "select", str(plain), "--out",
                          str(tmp_path / "select")], capture_output=True, text=True)
    assert cli.returncode == 1 and "no select section" in cli.stderr, cli.stderr
