"""The type stubs (vesselid/_core.pyi) name every public class, attribute and function the
extension binds, and nothing it does not: an editor's completion and a type checker see the
package as it is."""
import ast
import inspect
import os

import vesselid
from vesselid import _core


def stubbed():
    path = os.path.join(os.path.dirname(_core.__file__), "_core.pyi")
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read())
    classes, functions = {}, set()
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            classes[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        elif isinstance(node, ast.FunctionDef):
            functions.add(node.name)
    return classes, functions


def public(names):
    return {n for n in names if not n.startswith("__")}


def test_stubs_match_the_extension():
    classes, functions = stubbed()
    bound = {name for name, value in vars(_core).items() if inspect.isclass(value)}
    assert set(classes) == bound
    for name, members in classes.items():
        runtime = public(n for n in vars(getattr(_core, name)) if not n.startswith("_pybind11"))
        assert public(members) - {"__init__"} == runtime, name
    bound_functions = {name for name, value in vars(_core).items()
                       if callable(value) and not inspect.isclass(value)}
    assert functions == bound_functions


def test_the_package_names_its_types_and_version():
    assert vesselid.RunResult is _core.RunResult
    assert vesselid.__version__ == _core.__version__
    assert set(vesselid.__all__) <= set(dir(vesselid))
