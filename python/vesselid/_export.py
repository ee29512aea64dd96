"""vesselid.export and vesselid.predict: a finished run's model taken out (docs/export.md)."""
import json
import math
import os

from . import _core
from ._run import _out_argument


def _seed(seed) -> int:
    """A seed of the draws, as the CLI's --seed takes it: a whole number from 0."""
    if isinstance(seed, bool) or int(seed) != seed or seed < 0:
        raise ValueError(f"seed {seed!r}: a whole number >= 0 (--seed)")
    return int(seed)


def _known(value, name) -> float:
    """A ship's length or speed where given: a finite number (None: not known)."""
    if value is None:
        return math.nan
    number = float(value)
    if not math.isfinite(number):
        raise ValueError(f"{name} {value!r}: not a number (give None where it is not known)")
    return number


def export(run: "_core.RunResult | os.PathLike | str", format: str = "fmu",
           out: "os.PathLike | str | None" = None, members: int = 100, seed: int = 1) -> str:
    """The model of a run (a RunResult, or the folder of `vesselid run --out`) as an FMI 2.0
    co-simulation FMU (`format="fmu"`), C99 code (`"c"`: header, source and example) or
    model.json (`"json"`: family, options, parameters, covariance, `members` draws), written
    into `out` (default <run folder>/export; needed for a RunResult) as `vesselid export`
    writes it. Returns the file's path (the header for "c")."""
    # The FMU runtime installed with the package (VESSELID_FMU_RUNTIME names another).
    runtime = os.environ.get("VESSELID_FMU_RUNTIME",
                             os.path.join(os.path.dirname(__file__), "libvesselid_fmu.so"))
    if isinstance(run, _core.RunResult):
        if out is None:
            raise TypeError("export of a RunResult needs `out`, the folder to write into")
        return _core.export_result(run, str(format), _out_argument(out), int(members),
                                   _seed(seed), runtime)
    return _core.export_model(os.fspath(run), str(format), _out_argument(out),
                              int(members), _seed(seed), runtime)


def predict(run: "_core.RunResult | os.PathLike | str", length: "float | None" = None,
            speed: "float | None" = None, members: int = 100, seed: int = 1,
            out: "os.PathLike | str | None" = None) -> dict:
    """The standard manoeuvres (IMO 10/10 and 20/20 zigzag overshoots, initial turning ability)
    the run's model predicts, with 95 % intervals from `members` parameter draws and the delta
    method, held against the IMO criteria where the ship's `length` (m) and `speed` (m/s) are
    known: predictions.json as a dict, its text table under "text". Where the run identified
    process noise with the ship (a filter-error stage's gusts), each figure also has a
    "disturbance_interval": the members flown each in its own realisation of it. `run`: a
    RunResult or a run's folder. `out` also writes predictions.txt and predictions.json there."""
    conditions = (_known(length, "length"), _known(speed, "speed"), int(members), _seed(seed),
                  out is not None, _out_argument(out))
    if isinstance(run, _core.RunResult):
        text, payload = _core.predict_result(run, *conditions)
    else:
        text, payload = _core.predict(os.fspath(run), *conditions)
    predictions = json.loads(payload)
    predictions["text"] = text
    return predictions
