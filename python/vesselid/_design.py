"""vesselid.design: the next experiment planned from a finished run (docs/design.md)."""
import io
import json
import os

from . import _core
from ._run import _out_argument
from ._run import _config_arguments


def design(config: "os.PathLike | str | dict", run_dir: "os.PathLike | str",
           out: "os.PathLike | str | None" = None, threads: int = 0) -> dict:
    """Plans the next experiment from the run whose outputs are in `run_dir` as the config's
    `design:` section asks (a path, or a dict of the YAML schema): design.json as a dict, with
    its text table under "text" and the plan under "planned" (t and every input, in the
    config's units: a pandas DataFrame, or a dict of numpy columns without pandas) and the
    outputs the current model predicts on it under "predicted". `out` also writes the files of
    `vesselid design` there (planned_input.csv, predicted.csv, design.json, design.txt,
    report.html)."""
    message, payload, planned, predicted = _core.design(
        _config_arguments(config), os.fspath(run_dir), out is not None,
        _out_argument(out), int(threads))
    result = json.loads(payload)
    result["text"] = message
    result["planned"] = _table(planned)
    result["predicted"] = _table(predicted)
    return result


def _table(csv_text):
    try:
        import pandas as pd
    except ImportError:
        import numpy as np
        data = np.genfromtxt(io.StringIO(csv_text), delimiter=",", names=True)
        return {name: data[name] for name in data.dtype.names}
    return pd.read_csv(io.StringIO(csv_text))
