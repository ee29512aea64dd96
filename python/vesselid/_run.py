"""vesselid.run and vesselid.load_config."""
import json
import os

import numpy as np

from . import _core
from ._errors import DataError, raise_for
from ._result import Result


def _config_arguments(config):
    """(config text or path, is_text, name) for the engine."""
    if isinstance(config, dict):
        # JSON is YAML: the dict is read by the same reader as a file, keys and lines checked.
        return json.dumps(config, indent=1, allow_nan=False), True, "config"
    if isinstance(config, (str, os.PathLike)):
        return os.fspath(config), False, os.fspath(config)
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


def run(config, data=None, out=None, threads=0, report=True, progress=None):
    """Runs a staged identification and returns its Result.

    config:   a config file's path, or the same schema as a dict.
    data:     {experiment name: DataFrame or dict of numpy columns}, or a folder the
              experiments' files are resolved against (as `vesselid run --data`); experiments
              without data are read from their `file` as the CLI does.
    out:      a folder to write results.json, report.txt, report.html (report=True) and the
              traces into, as `vesselid run --out`; None writes nothing.
    threads:  threads of every stage's solves and global start (0: the config's, by default
              the machine's cores); the results are the same on any number.
    progress: called with {"phase", "iteration", "cost"} after each solver iteration; True
              shows a tqdm bar (python3-tqdm).
    Raises ConfigError, DataError or RunError with the CLI's message; Ctrl-C ends the current
    solve after its iteration and raises KeyboardInterrupt.
    """
    text, is_text, name = _config_arguments(config)
    data_dir, tables = _data_arguments(data)
    bar = None
    if progress is True:  # a tqdm bar when python3-tqdm is there, else none
        try:
            from tqdm.auto import tqdm
            bar = tqdm(desc="vesselid", unit=" iterations")
            progress = lambda p: (bar.update(1), bar.set_postfix(phase=p["phase"],
                                                                 cost="%.4g" % p["cost"]))
        except ImportError:
            progress = None
    elif progress is False:
        progress = None
    try:
        ok, kind, message, payload, traces = _core.run(
            text, is_text, name, data_dir, tables, "" if out is None else os.fspath(out), report,
            int(threads), progress)
    finally:
        if bar is not None:
            bar.close()
    if not ok:
        raise_for(kind, message)
    if isinstance(config, dict):
        config_data = config
    else:
        import yaml
        with open(text, encoding="utf-8") as f:
            config_data = yaml.safe_load(f)
    return Result(json.loads(payload), payload, message, (text, is_text, name), config_data,
                  traces)


def load_config(path):
    """A config file as a dict (merge keys resolved), after checking it as a run would."""
    import yaml
    ok, kind, message, _ = _core.check_config(os.fspath(path))
    if not ok:
        raise_for(kind, message)
    with open(path, encoding="utf-8") as f:
        return yaml.safe_load(f)


def simulate(config):
    """A config's synthetic experiments (its `simulation` section, as `vesselid simulate`):
    {file name without .csv: DataFrame}, read back with round-trip float parsing so that
    the frames hold the numbers the engine would read from the files."""
    import tempfile

    import pandas as pd
    text, is_text, name = _config_arguments(config)
    with tempfile.TemporaryDirectory(prefix="vesselid_simulate_") as folder:
        ok, kind, message, _ = _core.simulate(text, is_text, name, folder)
        if not ok:
            raise_for(kind, message)
        frames = {}
        for file in sorted(os.listdir(folder)):
            if file.endswith(".csv"):
                frames[file[:-4]] = pd.read_csv(os.path.join(folder, file),
                                                float_precision="round_trip")
        return frames


def study(config, data=None, only=None, threads=0, out=None, progress=None):
    """The config's `study` section (as `vesselid study`): returns study.json as a dict (its
    text report under the key "text"); `out` also writes study.json and study.txt there.
    `data` as for run(); `progress` gets one line per finished case."""
    text, is_text, name = _config_arguments(config)
    data_dir, tables = _data_arguments(data)
    ok, kind, message, payload = _core.study(text, is_text, name, data_dir, tables,
                                             list(only or []), int(threads), progress)
    if not ok:
        raise_for(kind, message)
    result = json.loads(payload)
    if out is not None:
        os.makedirs(out, exist_ok=True)
        with open(os.path.join(out, "study.json"), "w", encoding="utf-8") as f:
            json.dump(result, f, indent=2)
            f.write("\n")
        with open(os.path.join(out, "study.txt"), "w", encoding="utf-8") as f:
            f.write(message)
    result["text"] = message
    return result
