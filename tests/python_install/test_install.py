"""The package as a Python user installs it: `pip install build/python` into a virtual
environment (Debian's numpy and pandas seen through --system-site-packages, nothing fetched),
then used from another folder without PYTHONPATH: version, stubs, a run and an FMU export."""
import os
import subprocess
import sys
import textwrap

BUILD = os.environ["VESSELID_BUILD_DIR"]
SOURCE = os.environ["VESSELID_SOURCE_DIR"]

USE = textwrap.dedent("""
    import os, sys, zipfile
    import vesselid
    assert os.path.realpath(vesselid.__file__).startswith(os.path.realpath(sys.prefix)), vesselid.__file__
    print(vesselid.__version__)
    folder = os.path.dirname(vesselid.__file__)
    assert {"_core.pyi", "py.typed", "libvesselid_fmu.so"} <= set(os.listdir(folder))
    config = os.path.join(sys.argv[1], "configs", "nomoto_cargo.yaml")
    records = vesselid.simulate(config)
    loaded = vesselid.load_config(config)
    data = {e["name"]: records[os.path.splitext(e["file"])[0]] for e in loaded["experiments"]}
    result = vesselid.run(config, data=data, out="run", report=False)
    print(result.verdict, type(result).__name__)
    fmu = vesselid.export("run", format="fmu", out="fmu")
    with zipfile.ZipFile(fmu) as archive:
        assert "binaries/linux64/vesselid_model.so" in archive.namelist()
""")


def test_pip_installs_a_working_package(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)],
                   check=True, env=env)
    pip = subprocess.run([str(venv / "bin" / "pip"), "install", "--no-index",
                          "--no-build-isolation", "-q", os.path.join(BUILD, "python")],
                         env=env, capture_output=True, text=True)
    assert pip.returncode == 0, pip.stdout + pip.stderr
    script = tmp_path / "use.py"
    script.write_text(USE)
    work = tmp_path / "work"
    work.mkdir()
    used = subprocess.run([str(venv / "bin" / "python"), str(script), SOURCE], cwd=work,
                          env=env, capture_output=True, text=True)
    assert used.returncode == 0, used.stdout + used.stderr
    version, outcome = used.stdout.split("\n")[:2]
    with open(os.path.join(SOURCE, "engine", "base", "version.h"), encoding="utf-8") as f:
        assert '"%s"' % version in f.read()
    assert outcome.endswith("RunResult")
