"""The README's examples, run as a newcomer would run them.

The command-line example (a config for one's own zigzag logs, `my_tanker.yaml`, and the shell
lines that simulate stand-in logs, run it and show the report) and the Python example (a
staged run from DataFrames) are read from README.md's fenced blocks and run in a fresh folder
with the repository's `configs/` beside them; `build/vesselid` is the binary under test.
"""
import os
import re
import shlex
import subprocess

import pytest

SOURCE = os.environ["VESSELID_SOURCE_DIR"]
BINARY = os.environ["VESSELID_BINARY"]


def blocks(language):
    with open(os.path.join(SOURCE, "README.md"), encoding="utf-8") as f:
        text = f.read()
    return re.findall(r"```%s\n(.*?)```" % language, text, re.S)


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """A user's folder: the repository's configs, the README's config and its shell lines run."""
    folder = tmp_path_factory.mktemp("readme")
    os.symlink(os.path.join(SOURCE, "configs"), folder / "configs")
    (yaml_block,) = blocks("yaml")
    (folder / "my_tanker.yaml").write_text(yaml_block)
    (shell,) = blocks("sh")
    outputs = []
    for line in shell.splitlines():
        words = shlex.split(line, comments=True)
        if not words:
            continue
        if words[0] == "build/vesselid":
            words[0] = BINARY
        done = subprocess.run(words, cwd=folder, capture_output=True, text=True)
        assert done.returncode == 0, "%s\n%s" % (line, done.stderr)
        outputs.append(done.stdout)
    return folder, outputs


def test_the_command_line_example_runs_and_reports(folder):
    path, outputs = folder
    report = outputs[-1]  # `cat out/tanker/report.txt`
    assert "verdict" in report
    assert "n1" in report and "delta_0" in report
    for name in ("results.json", "report.txt", "report.html"):
        assert (path / "out" / "tanker" / name).exists()
    # The config names files by a pattern: one experiment per stand-in log.
    import json
    with open(path / "out" / "tanker" / "results.json", encoding="utf-8") as f:
        results = json.load(f)
    assert results["verdict"] != "failed"


def test_the_python_example_runs(folder, capsys):
    path, _ = folder
    (python_block,) = blocks("python")
    assert len(python_block.strip().splitlines()) <= 20
    cwd = os.getcwd()
    os.chdir(path)
    try:
        scope = {}
        exec(compile(python_block, "README.md (python)", "exec"), scope)
    finally:
        os.chdir(cwd)
    result = scope["result"]
    assert result.verdict in ("good", "doubtful")
    assert (result.parameters.loc["n1", "value"] < 0)  # the tanker is course-unstable
    assert set(result.fits["role"]) >= {"fit", "validation"}
    prediction = scope["prediction"]
    assert len(prediction) == len(scope["frames"]["zz10p_a"])
    assert "psi" in prediction.columns
