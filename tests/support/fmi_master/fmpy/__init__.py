"""The project's own FMI 2.0 co-simulation master, with fmpy's `simulate_fmu` signature and
conventions, so that the docs' fmpy examples run as tests where fmpy itself is not installed
(PyPI is out of reach; Debian has no fmpy).

The conventions kept (fmpy/simulation.py, simulateCS, FMI 2.0):
* fmi2SetupExperiment(start, stop); start values set in modelDescription order, those settable
  when instantiated (parameters and inputs) first, then fmi2EnterInitializationMode, the rest,
  the inputs at the start time, fmi2ExitInitializationMode;
* a start value of no variable raises "The start values for the following variables could not
  be set: ...";
* each communication step of `output_interval`: the inputs at its start (the signal table
  interpolated linearly, its first and last values held outside), fmi2DoStep, the outputs
  recorded; no input derivatives are set;
* the result is a structured numpy array: 'time' and the recorded variables.
Only what the docs use is offered; anything else raises.
"""
import ctypes
import os
import tempfile
import xml.etree.ElementTree as ET
import zipfile

import numpy as np

_LOGGER = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int,
                           ctypes.c_char_p, ctypes.c_char_p)
_ALLOCATE = ctypes.CFUNCTYPE(ctypes.c_void_p, ctypes.c_size_t, ctypes.c_size_t)
_FREE = ctypes.CFUNCTYPE(None, ctypes.c_void_p)
_STEP_FINISHED = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_int)


class _Callbacks(ctypes.Structure):
    _fields_ = [("logger", _LOGGER), ("allocateMemory", _ALLOCATE), ("freeMemory", _FREE),
                ("stepFinished", _STEP_FINISHED), ("componentEnvironment", ctypes.c_void_p)]


_libc = ctypes.CDLL(None)
_libc.calloc.restype = ctypes.c_void_p
_libc.calloc.argtypes = [ctypes.c_size_t, ctypes.c_size_t]
_libc.free.argtypes = [ctypes.c_void_p]


@_LOGGER
def _log(environment, instance, status, category, message):
    if status >= 2:  # fmi2Warning and worse, as fmpy prints them
        print("[%s] %s" % (category.decode(), message.decode()))


_callbacks = _Callbacks(_log, _ALLOCATE(lambda n, size: _libc.calloc(n, size)),
                        _FREE(lambda p: _libc.free(p)), _STEP_FINISHED(), None)
_extracted = {}  # one extraction per FMU file and process (fmpy extracts on every call)


class _Variable:
    def __init__(self, element):
        self.name = element.get("name")
        self.reference = int(element.get("valueReference"))
        self.causality = element.get("causality", "local")
        self.type = next(child.tag for child in element
                         if child.tag in ("Real", "Integer", "Boolean", "String"))


def _extract(filename):
    key = os.path.abspath(filename)
    if key not in _extracted:
        folder = tempfile.mkdtemp(prefix="fmi_master_")
        with zipfile.ZipFile(filename) as archive:
            archive.extractall(folder)
        _extracted[key] = folder
    return _extracted[key]


def _check(status, call):
    if status > 1:  # worse than fmi2Warning
        raise Exception("%s failed with status %d" % (call, status))


def simulate_fmu(filename, start_time=0.0, stop_time=None, output_interval=None, input=None,
                 start_values=None, output=None, **unsupported):
    if unsupported:
        raise NotImplementedError("not offered here: " + ", ".join(unsupported))
    folder = _extract(filename)
    description = ET.parse(os.path.join(folder, "modelDescription.xml")).getroot()
    co_simulation = description.find("CoSimulation")
    identifier = co_simulation.get("modelIdentifier")
    library = ctypes.CDLL(os.path.join(folder, "binaries", "linux64", identifier + ".so"))
    variables = [_Variable(v) for v in description.find("ModelVariables")]
    by_name = {v.name: v for v in variables}
    start_time = float(start_time)
    stop_time = float(stop_time if stop_time is not None else start_time + 1.0)
    interval = float(output_interval if output_interval is not None
                     else (stop_time - start_time) / 500.0)

    f = library
    f.fmi2Instantiate.restype = ctypes.c_void_p
    f.fmi2Instantiate.argtypes = [ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p,
                                  ctypes.POINTER(_Callbacks), ctypes.c_int, ctypes.c_int]
    references = lambda names: (ctypes.c_uint * len(names))(*[by_name[n].reference for n in names])
    component = f.fmi2Instantiate(b"instance", 1, description.get("guid").encode(),
                                  ("file://" + os.path.join(folder, "resources")).encode(),
                                  ctypes.byref(_callbacks), 0, 0)
    if not component:
        raise Exception("fmi2Instantiate failed")
    c = ctypes.c_void_p(component)

    def set_value(variable, value):
        vr = (ctypes.c_uint * 1)(variable.reference)
        if variable.type == "Real":
            _check(f.fmi2SetReal(c, vr, 1, (ctypes.c_double * 1)(float(value))), "fmi2SetReal")
        elif variable.type == "Integer":
            _check(f.fmi2SetInteger(c, vr, 1, (ctypes.c_int * 1)(int(value))), "fmi2SetInteger")
        else:
            raise NotImplementedError(variable.type)

    def apply_start_values(remaining, settable):
        for variable in variables:  # modelDescription order, as fmpy
            if variable.name in remaining and settable(variable):
                set_value(variable, remaining.pop(variable.name))

    time_names = input.dtype.names if input is not None else ()
    inputs = [by_name[n] for n in time_names[1:] if n in by_name and by_name[n].causality == "input"]
    table_t = input[time_names[0]] if input is not None else None

    def apply_inputs(t):
        for variable in inputs:
            set_value(variable, np.interp(t, table_t, input[variable.name]))

    remaining = dict(start_values or {})
    f.fmi2SetupExperiment.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_double,
                                      ctypes.c_double, ctypes.c_int, ctypes.c_double]
    _check(f.fmi2SetupExperiment(c, 0, 0.0, start_time, 1, stop_time), "fmi2SetupExperiment")
    apply_start_values(remaining, lambda v: v.causality in ("parameter", "input"))
    _check(f.fmi2EnterInitializationMode(c), "fmi2EnterInitializationMode")
    apply_start_values(remaining, lambda v: True)
    apply_inputs(start_time)
    _check(f.fmi2ExitInitializationMode(c), "fmi2ExitInitializationMode")
    if remaining:
        raise Exception("The start values for the following variables could not be set: " +
                        ", ".join(remaining))

    recorded = output if output is not None else [v.name for v in variables
                                                  if v.causality == "output"]
    recorded_refs = references(recorded)
    values = (ctypes.c_double * len(recorded))()
    f.fmi2DoStep.argtypes = [ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_int]
    rows = []

    def sample(t):
        _check(f.fmi2GetReal(c, recorded_refs, len(recorded), values), "fmi2GetReal")
        rows.append((t,) + tuple(values))

    time, steps = start_time, 0
    sample(time)
    while time < stop_time and not np.isclose(time, stop_time):
        next_time = min(start_time + (steps + 1) * interval, stop_time)
        apply_inputs(time)
        _check(f.fmi2DoStep(c, time, next_time - time, 1), "fmi2DoStep")
        time, steps = next_time, steps + 1
        sample(time)
    f.fmi2Terminate(c)
    f.fmi2FreeInstance.argtypes = [ctypes.c_void_p]
    f.fmi2FreeInstance(c)
    return np.array(rows, dtype=[("time", np.float64)] + [(n, np.float64) for n in recorded])
