"""vesselid from Python: identify ship and small-craft motion models from recorded runs.

    import vesselid
    result = vesselid.run("configs/nomoto_tanker.yaml", data={"zz10s_a": frame, ...})
    result.parameters          # DataFrame: value, std_error, lower, upper, role, ...
    result.verdict, result.findings
    result.model.simulate(frame)  # the identified model, flown as the run flew its records

The config is a path or a dict (the YAML schema as Python data); records are pandas
DataFrames (or dicts of numpy columns) keyed by experiment name, with a time column (`t`
unless the experiment's `time` key names another) and the columns the experiment maps, NaN
for a missing sample. Experiments without data are read from their files as the CLI does.
The results are the engine's own types (RunResult, StageResult, Finding, IdentifiedModel),
bound read-only.
"""
from ._errors import ConfigError, DataError, RunError, VesselidError
from ._core import Disturbance, Finding, IdentifiedModel, RunResult, StageResult, __version__
from ._run import load_config, run, select, simulate, study
from ._design import design
from ._export import export, predict

__all__ = ["run", "select", "simulate", "study", "load_config", "export", "predict", "design",
           "RunResult", "StageResult", "Disturbance", "Finding", "IdentifiedModel", "VesselidError",
           "ConfigError", "DataError", "RunError", "__version__"]
