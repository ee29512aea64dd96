"""vesselid.run, select, study, simulate and load_config: the commands, as the CLI runs them."""
import json
import os

import numpy as np

from typing import Any, Callable, Mapping, Union

from . import _core
from ._errors import DataError

# A config: a file's path or the schema as a dict; records: {experiment: DataFrame or dict of
# numpy columns}, or a folder; progress: a callable of a dict, or True for a tqdm bar.
Config = Union[str, os.PathLike, dict]
Data = Union[None, str, os.PathLike, Mapping[str, Any]]
Progress = Union[None, bool, Callable[[dict], Any]]


def _config_arguments(config):
    """The config for the engine: a path, or a dict as its text (JSON is YAML: the dict is read
    by the same reader as a file, keys and lines checked)."""
    if isinstance(config, dict):
        return _core._Config(json.dumps(config, indent=1, allow_nan=False), True, "config")
    if isinstance(config, (str, os.PathLike)):
        return _core._Config(os.fspath(config), False, os.fspath(config))
    raise TypeError("config must be a path or a dict, not %s" % type(config).__name__)


def _columns(name, frame):
    """A record as {column: float64 array}: a DataFrame, or a dict of array-likes."""
    try:
        import pandas as pd
    except ImportError:  # numpy columns only
        pd = None
    if pd is not None and isinstance(frame, pd.DataFrame):
        columns = {}
        for column in frame.columns:
            series = frame[column]
            if pd.api.types.is_datetime64_any_dtype(series):
                # Epoch times: seconds since 1970 (the engine makes them relative).
                values = series.dt.tz_localize(None) if series.dt.tz is not None else series
                columns[str(column)] = values.astype("int64").to_numpy() / 1e9
            elif pd.api.types.is_complex_dtype(series):
                raise DataError("data['%s'] column '%s': complex values (the imaginary part "
                                "would be lost); give its real part" % (name, column))
            elif pd.api.types.is_numeric_dtype(series) or pd.api.types.is_bool_dtype(series):
                columns[str(column)] = series.to_numpy(dtype=np.float64, na_value=np.nan)
            # Text columns (a timestamp string, a note) are left out, as the CSV reader skips
            # columns it does not map.
        return columns
    if isinstance(frame, dict):
        columns = {}
        for k, v in frame.items():
            values = np.asarray(v)
            if np.iscomplexobj(values):
                raise DataError("data['%s'] column '%s': complex values (the imaginary part "
                                "would be lost); give its real part" % (name, k))
            if values.dtype.kind not in "biuf":
                raise DataError("data['%s'] column '%s': %s values, not numbers"
                                % (name, k, values.dtype))
            columns[str(k)] = values.astype(np.float64)
        return columns
    raise TypeError("data['%s'] must be a pandas DataFrame or a dict of columns, not %s"
                    % (name, type(frame).__name__))


def _data_arguments(data):
    """(data folder, {experiment: columns}) for the engine: `data` is a folder, or frames or
    column dicts by experiment name, or None."""
    if isinstance(data, (str, os.PathLike)):
        return os.fspath(data), {}
    if data is None:
        return "", {}
    # A frame given for several experiments (windows of one log) is converted once, so that
    # the engine reads it as one record, as it reads one file once.
    converted = {}
    for k, v in data.items():
        if id(v) not in converted:
            converted[id(v)] = _columns(k, v)
    return "", {str(k): converted[id(v)] for k, v in data.items()}


def _progress_callback(progress):
    """(callback, bar): `progress` as the engine calls it; True shows a tqdm bar
    (python3-tqdm) when it is there."""
    if progress is True:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            return None, None
        bar = tqdm(desc="vesselid", unit=" iterations")

        def tell(p):
            bar.update(1)
            if "cost" in p:
                bar.set_postfix(phase=p["phase"], cost="%.4g" % p["cost"])
        return tell, bar
    if progress is False or progress is None:
        return None, None
    if not callable(progress):
        raise TypeError("progress must be callable, True or None, not %s"
                        % type(progress).__name__)
    return progress, None


def _out_argument(out):
    """`out` for the engine: "" for none; an empty path is refused, as the CLI refuses it."""
    if out is None:
        return ""
    out = os.fspath(out)
    if not out:
        raise ValueError("out: an empty path; give a folder, or None to write nothing")
    return out


def _run_command(command, config, data, out, threads, report, progress):
    callback, bar = _progress_callback(progress)
    data_dir, tables = _data_arguments(data)
    try:
        return command(_config_arguments(config), data_dir, tables, out is not None,
                       _out_argument(out), report, int(threads), callback)
    finally:
        if bar is not None:
            bar.close()


def run(config: Config, data: Data = None, out: "os.PathLike | str | None" = None,
        threads: int = 0, report: bool = True, progress: Progress = None) -> "_core.RunResult":
    """Runs a staged identification and returns its RunResult.

    config:   a config file's path, or the same schema as a dict.
    data:     {experiment name: DataFrame or dict of numpy columns}, or a folder the
              experiments' files are resolved against (as `vesselid run --data`); experiments
              without data are read from their `file` as the CLI does.
    out:      a folder to write results.json, report.txt, report.html (report=True), the
              traces and the checkpoint into, as `vesselid run --out` (same checks, lock and
              publication); None writes nothing.
    threads:  threads of every stage's solves and global start (0: the config's, by default
              the machine's cores); the results are the same on any number.
    progress: called with {"phase", "iteration", "cost"} after each solver iteration; True
              shows a tqdm bar (python3-tqdm).
    Raises ConfigError, DataError or RunError with the CLI's message; Ctrl-C ends the current
    solve after its iteration and raises KeyboardInterrupt.
    """
    return _run_command(_core.run, config, data, out, threads, report, progress)


def select(config: Config, data: Data = None, out: "os.PathLike | str | None" = None,
           threads: int = 0, report: bool = True,
           progress: Progress = None) -> "_core.RunResult":
    """The config's `select` section (as `vesselid select`): every candidate structure
    cross-validated over the runs, then the chosen one run on every run. Returns the chosen
    candidate's RunResult, its `selection` the cross-validation (scores, folds, the choice and
    why). Arguments as for run(); `progress` also gets {"phase": "select", "message"} per
    finished case."""
    return _run_command(_core.select, config, data, out, threads, report, progress)


def load_config(path: "os.PathLike | str") -> dict:
    """A config file as a dict (merge keys resolved), after checking it as a run would."""
    import yaml
    _core.check_config(_config_arguments(os.fspath(path)))
    with open(path, encoding="utf-8") as f:
        return yaml.safe_load(f)


def simulate(config: Config) -> "dict[str, Any]":
    """A config's synthetic experiments (its `simulation` section, as `vesselid simulate`):
    {file name without .csv: DataFrame}, read back with round-trip float parsing so that
    the frames hold the numbers the engine would read from the files."""
    import tempfile

    import pandas as pd
    with tempfile.TemporaryDirectory(prefix="vesselid_simulate_") as folder:
        files = _core.simulate(_config_arguments(config), folder)
        return {file[:-4]: pd.read_csv(os.path.join(folder, file), float_precision="round_trip")
                for file in sorted(files) if file.endswith(".csv")}


def study(config: Config, data: Data = None, only: "list[str] | None" = None, threads: int = 0,
          out: "os.PathLike | str | None" = None,
          progress: "Callable[[str], Any] | None" = None) -> dict:
    """The config's `study` section (as `vesselid study`): returns study.json as a dict (its
    text report under the key "text"); `out` also writes study.json and study.txt there, as
    the CLI does (same checks, lock and publication). `data` as for run(); `progress` gets one
    line per finished case."""
    data_dir, tables = _data_arguments(data)
    if isinstance(only, str):
        only = [only]
    payload, text = _core.study(_config_arguments(config), data_dir, tables, list(only or []),
                                out is not None, _out_argument(out),
                                int(threads), progress)
    result = json.loads(payload)
    result["text"] = text
    return result
