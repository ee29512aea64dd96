"""Model: an identified model to simulate from Python."""
import math

import numpy as np

from . import _core
from ._errors import raise_for


def degree_names(config):
    """Model inputs and outputs the config's experiments read in degrees (from the first
    experiment, with experiment_defaults merged in): what a user's frames hold in degrees."""
    experiments = config.get("experiments") or []
    if not experiments:
        return set()
    merged = dict(config.get("experiment_defaults") or {})
    merged.update(experiments[0])
    degrees = set(merged.get("degrees") or [])
    names = set()
    for key in ("inputs", "outputs"):
        for name, column in (merged.get(key) or {}).items():
            if column in degrees:
                names.add(name)
    return names


class Model:
    """The run's model with its identified parameters.

    parameters  pandas Series: the value of every model parameter (the model's defaults for
                those the run did not estimate), SI units
    covariance  DataFrame of the estimated parameters' covariance (the last stage that
                estimated them), or None
    simulate(inputs, initial_state=None, parameters=None, substeps=4, interpolation="linear")
                open-loop simulation under `inputs` (a DataFrame with a time column `t` and a
                column per model input) -> DataFrame of t, the inputs, the outputs and the
                states ("x.<state>", the state at each sample time). Angles
                the config reads in degrees are taken and given in degrees (initial states
                of those names too); `parameters` overrides values by name (SI units).
    """

    def __init__(self, config_arguments, degrees, estimates, covariance):
        self._config = config_arguments
        ok, kind, message, info = _core.model_info(*config_arguments)
        if not ok:
            raise_for(kind, message)
        self.info = info
        self.degrees = set(degrees)
        values = dict(zip(info["parameters"], info["defaults"]))
        values.update({k: v for k, v in estimates.items() if k in values})
        import pandas as pd
        self.parameters = pd.Series(values, name="value", dtype=float)
        self.covariance = covariance

    def __repr__(self):
        return "<vesselid.Model %s: inputs %s, outputs %s>" % (
            self.info["name"], self.info["inputs"], self.info["outputs"])

    def simulate(self, inputs, initial_state=None, parameters=None, substeps=4,
                 interpolation="linear"):
        import pandas as pd
        values = self.parameters.copy()
        for name, value in (parameters or {}).items():
            if name not in values.index:
                raise KeyError("%s has no parameter '%s' (%s)" % (
                    self.info["name"], name, ", ".join(values.index)))
            values[name] = value
        state = dict.fromkeys(self.info["states"], 0.0)
        for name, value in (initial_state or {}).items():
            if name not in state:
                raise KeyError("%s has no state '%s' (%s)" % (
                    self.info["name"], name, ", ".join(state)))
            state[name] = value * (math.pi / 180.0 if name in self.degrees else 1.0)
        scale = math.pi / 180.0
        columns = {"t": np.asarray(inputs["t"], dtype=np.float64)}
        for name in self.info["inputs"]:
            if name in inputs:
                column = np.asarray(inputs[name], dtype=np.float64)
                columns[name] = column * scale if name in self.degrees else column
        ok, kind, message, out = _core.simulate_model(
            *self._config, [float(values[p]) for p in self.info["parameters"]],
            [float(state[s]) for s in self.info["states"]], columns, int(substeps), interpolation)
        if not ok:
            raise_for(kind, message)
        frame = pd.DataFrame(out)
        for name in frame.columns:
            # outputs by name, states as "x.<state>"
            if name in self.degrees or (name.startswith("x.") and name[2:] in self.degrees):
                frame[name] = frame[name] / scale
        return frame
