"""Result: a run's results.json as Python objects and pandas DataFrames."""
import dataclasses
import html
import json
import math

import numpy as np


@dataclasses.dataclass(frozen=True)
class Finding:
    """One typed finding of the run (see `vesselid findings` for the kinds)."""
    kind: str
    severity: str  # "info", "warning" or "failure"
    message: str
    stage: str = ""
    experiment: str = ""
    segment: str = ""
    parameter: str = ""
    output: str = ""
    input: str = ""  # the model input the finding is about (a rudder column), "" when none
    value: float = math.nan
    threshold: float = math.nan
    count: int = 0

    @staticmethod
    def from_json(item):
        number = lambda v: math.nan if v is None else float(v)
        return Finding(kind=item["kind"], severity=item["severity"], message=item["message"],
                       stage=item.get("stage", ""), experiment=item.get("experiment", ""),
                       segment=item.get("segment", ""), parameter=item.get("parameter", ""),
                       output=item.get("output", ""), input=item.get("input", ""),
                       value=number(item.get("value")),
                       threshold=number(item.get("threshold")), count=item.get("count", 0))


def _number(value):
    return math.nan if value is None else value


class Result:
    """What `vesselid run` writes, from Python.

    parameters  DataFrame indexed by parameter name: value, std_error, lower, upper,
                interval_low, interval_high, role, unit, undetermined, at_bound, stages (SI
                units), and shown_unit / shown_scale: the unit the data came in (an angle
                read in degrees: "deg", 57.3) by which the reports show the value
    verdict     "good", "doubtful" or "failed"
    findings    list of Finding (the run's and every stage's); find(kind=, severity=) filters
    stages      DataFrame, one row per stage: verdict, cost, comparable_cost, iterations
    fits        DataFrame of the fit metrics per stage, experiment and output ("fit" on the
                training runs, "validation" on held-out runs, "final_validation")
    traces      {"<stage>.<experiment>": DataFrame of t and each compared output measured
                and simulated ("psi_measured [deg]"), in the units the data came in}: the
                CLI's traces/ files ("<stage>.validation.<run>" for held-out runs,
                "final_validation.<run>")
    json        results.json as a dict; to_json() its text
    summary     report.txt's text
    """

    def __init__(self, results, text, summary, config_arguments=None, config=None,
                 traces=None):
        self._config_arguments = config_arguments
        self._traces = traces or {}
        self._config = config
        self.json = results
        self._text = text
        self.summary = summary
        self.verdict = results["verdict"]
        findings = list(results.get("findings", []))
        for stage in results.get("stages", []):
            findings.extend(stage.get("findings", []))
        self.findings = [Finding.from_json(f) for f in findings]

    @property
    def model(self):
        """The run's model with its final parameters (a Model, for simulation)."""
        from ._model import Model, degree_names
        import pandas as pd
        estimates = {p["name"]: p["value"] for p in self.json.get("parameters", [])}
        covariance = None
        for stage in reversed(self.json.get("stages", [])):
            correlation = stage.get("correlation")
            if not correlation:
                continue
            errors = {e["name"]: _number(e.get("std_error")) for e in stage.get("estimates", [])}
            names = correlation["names"]
            sd = np.array([errors.get(n, math.nan) for n in names])
            matrix = np.array([[_number(v) for v in row] for row in correlation["matrix"]])
            covariance = pd.DataFrame(matrix * np.outer(sd, sd), index=names, columns=names)
            break
        return Model(self._config_arguments, degree_names(self._config or {}), estimates,
                     covariance)

    def to_json(self):
        """results.json's text (the same bytes as `vesselid run` writes, before indentation)."""
        return self._text

    def find(self, kind=None, severity=None):
        """The findings of one kind and/or severity."""
        return [f for f in self.findings
                if (kind is None or f.kind == kind) and (severity is None or f.severity == severity)]

    @property
    def parameters(self):
        import pandas as pd
        rows = []
        for p in self.json.get("parameters", []):
            bounds = p.get("bounds", [None, None])
            interval = p.get("interval", [None, None])
            rows.append({"name": p["name"], "value": p["value"],
                         "std_error": _number(p.get("std_error")),
                         "lower": _number(bounds[0]), "upper": _number(bounds[1]),
                         "interval_low": _number(interval[0]),
                         "interval_high": _number(interval[1]),
                         "role": p.get("role", ""), "unit": p.get("unit", ""),
                         "undetermined": p.get("undetermined", False),
                         "at_bound": p.get("at_bound", ""),
                         "shown_unit": p.get("shown_unit", p.get("unit", "")),
                         "shown_scale": p.get("shown_scale", 1.0),
                         "stages": ", ".join(p.get("stages", []))})
        columns = ["name", "value", "std_error", "lower", "upper", "interval_low",
                   "interval_high", "role", "unit", "undetermined", "at_bound", "shown_unit",
                   "shown_scale", "stages"]
        return pd.DataFrame(rows, columns=columns).set_index("name")

    @property
    def traces(self):
        import pandas as pd
        return {name: pd.DataFrame(columns) for name, columns in self._traces.items()}

    @property
    def stages(self):
        import pandas as pd
        rows = [{"stage": s["name"], "verdict": s.get("verdict", ""),
                 "cost": _number(s.get("cost")),
                 "comparable_cost": _number(s.get("comparable_cost")),
                 "iterations": s.get("iterations", 0)}
                for s in self.json.get("stages", [])]
        return pd.DataFrame(rows, columns=["stage", "verdict", "cost", "comparable_cost",
                                           "iterations"]).set_index("stage")

    @property
    def fits(self):
        import pandas as pd
        rows = []
        def add(stage, role, fits):
            for m in (fits or {}).get("metrics", []):
                row = {"stage": stage, "role": role}
                row.update({k: _number(v) if k not in ("experiment", "output", "unit") else v
                            for k, v in m.items()})
                rows.append(row)
        for s in self.json.get("stages", []):
            add(s["name"], "fit", s.get("fit"))
            add(s["name"], "validation", s.get("validation"))
        add("", "final_validation", self.json.get("final_validation"))
        return pd.DataFrame(rows)

    def __repr__(self):
        return "<vesselid.Result verdict=%s, %d parameters, %d findings>" % (
            self.verdict, len(self.json.get("parameters", [])), len(self.findings))

    def _repr_html_(self):
        """The verdict, the parameters in the units the data came in, and the warnings."""
        colour = {"good": "#1a7f37", "doubtful": "#9a6700", "failed": "#cf222e"}
        head = "<p><b>vesselid run</b>: verdict <b style='color:%s'>%s</b></p>" % (
            colour.get(self.verdict, "black"), html.escape(self.verdict))
        p = self.parameters
        scale = p["shown_scale"]
        shown = p.assign(value=p["value"] * scale, std_error=p["std_error"] * scale,
                         interval_low=p["interval_low"] * scale,
                         interval_high=p["interval_high"] * scale, unit=p["shown_unit"])
        table = shown[["value", "std_error", "interval_low", "interval_high", "unit", "role",
                       "at_bound"]].to_html(float_format=lambda v: "%.6g" % v, na_rep="")
        warnings = [f for f in self.findings if f.severity != "info"]
        items = "".join("<li>%s: %s</li>" % (html.escape(f.severity), html.escape(f.message))
                        for f in warnings[:20])
        tail = "<ul>%s</ul>" % items if items else "<p>no warnings</p>"
        return head + table + tail
