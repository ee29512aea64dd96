"""A compass whose noise is slow (the independent corpus's correct_coloured_heading_noise
class: an AR(1) of 2-20 s on the heading of a ship the model represents) leaves residuals as
coloured as a structure the model lacks. The verdict cannot tell the two apart from one record
(docs/verdict.md, "Known limits"); the warning says both, and that the intervals are too
narrow either way."""
import json
import os
import subprocess
import sys
import tempfile

SOURCE = os.environ["VESSELID_SOURCE_DIR"]
BINARY = os.environ["VESSELID_BINARY"]
sys.path.insert(0, os.path.join(SOURCE, "tests", "corpus"))
import corpus  # noqa: E402

KIND = "correct_coloured_heading_noise"


def run(index):
    """The case's label and its run's results.json, whole (corpus.run_case cuts messages)."""
    case = corpus.make_case(KIND, index, 1000 * (list(corpus.CLASSES).index(KIND) + 1) + index)
    with tempfile.TemporaryDirectory() as root:
        corpus.write_case(case, root)
        out = os.path.join(root, "out")
        status = subprocess.run([BINARY, "run", os.path.join(root, "config.yaml"), "--out", out,
                                 "--quiet", "--no-report"], capture_output=True, text=True)
        assert status.returncode == 0, status.stderr
        with open(os.path.join(out, "results.json")) as f:
            results = json.load(f)
    estimates = {p["name"]: p["value"] for p in results["parameters"]}
    return corpus.label(case, estimates), results


def test_slow_compass_noise_is_named_beside_the_structure():
    (good, why), results = run(6)
    assert good, why  # K and T_eff within 10 %: labelled by LABELS.md
    coloured = [f for s in results["stages"] for f in s.get("findings", [])
                if f["kind"] == "coloured_residuals" and f["severity"] == "warning"]
    assert len(coloured) == 1, results["stages"][-1].get("findings")
    assert "the measurement's own noise is slow" in coloured[0]["message"]
    assert "standard errors are too narrow" in coloured[0]["message"]
    assert results["verdict"] == "doubtful"  # the known limit, measured by the corpus


def test_white_compass_noise_stays_quiet():
    case = corpus.make_case("correct_second_order", 0, 1000)
    with tempfile.TemporaryDirectory() as root:
        result = corpus.run_case(case, BINARY, root)
    assert result["good"] and result["verdict"] == "good"
    assert not [f for f in result["findings"] if "coloured_residuals" in f], result["findings"]
