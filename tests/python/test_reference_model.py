"""`final_validation: {reference: <folder>}` (engine/run/reference_model.h): the final values
are flown beside another run's model on the same held-out run, from its measured start, and
`worse_than_reference` warns when they predict it worse. Records from the independent
corpus's simulator (tests/corpus/simulators.py), not from the engine's models: a model
identified from the first 40 s of the training zigzag is held against the one identified from
the whole of it, and the other way round."""
import json
import os
import subprocess
import sys
import tempfile

import pytest

SOURCE = os.environ["VESSELID_SOURCE_DIR"]
BINARY = os.environ["VESSELID_BINARY"]
sys.path.insert(0, os.path.join(SOURCE, "tests", "corpus"))
import corpus  # noqa: E402

KIND, INDEX = "correct_second_order", 0


@pytest.fixture(scope="module")
def folder():
    case = corpus.make_case(KIND, INDEX, 1000 * (list(corpus.CLASSES).index(KIND) + 1) + INDEX)
    with tempfile.TemporaryDirectory() as root:
        corpus.write_case(case, root)
        with open(os.path.join(root, "config.yaml")) as f:
            whole = f.read()
        assert "{name: train, file: train.csv," in whole
        short = whole.replace("{name: train, file: train.csv,",
                              "{name: train, file: train.csv, window: [0, 40],")
        write(root, "whole.yaml", whole)
        write(root, "short.yaml", short)
        for name in ("whole", "short"):
            run(root, name + ".yaml", name)
        yield root


def write(root, name, text):
    with open(os.path.join(root, name), "w") as f:
        f.write(text)


def run(root, config, out):
    return subprocess.run([BINARY, "run", os.path.join(root, config), "--out",
                           os.path.join(root, out), "--quiet", "--no-report"],
                          capture_output=True, text=True)


def with_reference(root, config, reference, name):
    with open(os.path.join(root, config)) as f:
        text = f.read()
    old = "final_validation: {experiments: [test]}"
    assert old in text
    write(root, name, text.replace(old, "final_validation: {experiments: [test], reference: %s}"
                                   % reference))
    return name


def results(root, out):
    with open(os.path.join(root, out, "results.json")) as f:
        return json.load(f)


def reference_findings(r):
    return [f for f in r["findings"] if f["kind"] == "worse_than_reference"]


def run_against(root, config, reference, out):
    """`config` run with `reference` as its final validation's reference: the process, its
    results.json and their `final_validation.reference`."""
    status = run(root, with_reference(root, config, reference, out + ".yaml"), out)
    assert status.returncode == 0, status.stderr
    r = results(root, out)
    return status, r, r["final_validation"]["reference"]


def test_a_model_from_fewer_data_is_held_against_the_reference(folder):
    status, r, check = run_against(folder, "short.yaml", "whole", "short_vs_whole")
    assert check["worse"] and check["mean_mae_ratio"] > 1.01, check
    assert check["folder"].endswith("whole")
    found = reference_findings(r)
    assert len(found) == 1 and found[0]["severity"] == "warning", r["findings"]
    assert "reference model" in found[0]["message"]
    assert r["verdict"] != "good"
    assert "worse_than_reference" in status.stderr


def test_the_better_model_stays_quiet(folder):
    _, r, check = run_against(folder, "whole.yaml", "short", "whole_vs_short")
    assert not check["worse"] and check["mean_mae_ratio"] < 1.0, check
    assert not reference_findings(r)
    # The reference changes nothing else: the same estimates as without it.
    plain = {p["name"]: p["value"] for p in results(folder, "whole")["parameters"]}
    assert {p["name"]: p["value"] for p in r["parameters"]} == plain
    assert r["verdict"] == results(folder, "whole")["verdict"]


@pytest.mark.parametrize("reference,why", [
    ("nowhere", "results.json"),
    ("first_order", "the reference is a nomoto model"),
])
def test_a_reference_that_cannot_serve_is_refused(folder, reference, why):
    if reference == "first_order":
        with open(os.path.join(folder, "whole.yaml")) as f:
            text = f.read()
        first = text.replace("type: second_order", "type: first_order")
        lines = [l for l in first.split("\n") if not l.strip().startswith(("T1:", "T2:", "T3:"))]
        first = "\n".join(lines).replace("      K:", "      T: {start: 20, lower: 0.5, upper: 1000}\n      K:")
        write(folder, "first_order.yaml", first)
        status = run(folder, "first_order.yaml", "first_order")
        assert status.returncode == 0, status.stderr
    config = with_reference(folder, "whole.yaml", reference, "bad_%s.yaml" % reference)
    out = "bad_" + reference
    status = run(folder, config, out)
    assert status.returncode != 0
    assert "final_validation.reference" in status.stderr and why in status.stderr, status.stderr
    assert config in status.stderr
    assert not os.path.exists(os.path.join(folder, out))


def tree_digest(folder):
    import hashlib
    digest = hashlib.sha256()
    for base, dirs, files in sorted(os.walk(folder)):
        dirs.sort()
        for name in sorted(files):
            path = os.path.join(base, name)
            digest.update(path.encode())
            with open(path, "rb") as f:
                digest.update(f.read())
    return digest.hexdigest()


def copy_reference(root, source, name, edit=None):
    import shutil
    target = os.path.join(root, name)
    shutil.rmtree(target, ignore_errors=True)
    shutil.copytree(os.path.join(root, source), target)
    if edit is not None:
        path = os.path.join(target, "results.json")
        with open(path) as f:
            r = json.load(f)
        edit(r)
        with open(path, "w") as f:
            json.dump(r, f)
    return name


def test_out_at_the_reference_folder_is_refused_and_the_reference_kept(folder):
    reference = copy_reference(folder, "whole", "kept")
    before = tree_digest(os.path.join(folder, reference))
    config = with_reference(folder, "short.yaml", reference, "onto_reference.yaml")
    status = run(folder, config, reference)
    assert status.returncode != 0
    assert "results.json" in status.stderr and "--out" in status.stderr, status.stderr
    assert tree_digest(os.path.join(folder, reference)) == before


@pytest.mark.parametrize("reference,why", [
    ("no_K", "parameters: the reference reports no 'K'"),
    ("whole/results.json", "name the reference run's output folder"),
    ("garbled", "not the results.json of a finished `vesselid run`"),
])
def test_a_reference_with_less_than_a_model_is_refused(folder, reference, why):
    if reference == "no_K":
        copy_reference(folder, "whole", "no_K", lambda r: r.update(
            parameters=[p for p in r["parameters"] if p["name"] != "K"]))
    if reference == "garbled":
        copy_reference(folder, "whole", "garbled", lambda r: r["model"].update(family=7))
    config = with_reference(folder, "whole.yaml", reference, "less_%s.yaml" % len(why))
    status = run(folder, config, "less")
    assert status.returncode != 0
    assert why in status.stderr and "final_validation.reference" in status.stderr, status.stderr
    assert "[json.exception" not in status.stderr
    assert not os.path.exists(os.path.join(folder, "less"))


def test_a_reference_that_diverges_is_said_to(folder):
    def unstable(r):
        for p in r["parameters"]:
            if p["name"] == "T1":
                p["value"] = -5.0  # a negative time constant: the heading runs away
    reference = copy_reference(folder, "whole", "unstable", unstable)
    config = with_reference(folder, "whole.yaml", reference, "whole_vs_unstable.yaml")
    status = subprocess.run([BINARY, "run", os.path.join(folder, config), "--out",
                             os.path.join(folder, "whole_vs_unstable"), "--quiet"],
                            capture_output=True, text=True)
    assert status.returncode == 0, status.stderr
    r = results(folder, "whole_vs_unstable")
    check = r["final_validation"]["reference"]
    assert check["reference_diverged"] == check["runs"] == 1 and not check["worse"], check
    assert not reference_findings(r)
    for name in ("report.txt", "report.html"):
        with open(os.path.join(folder, "whole_vs_unstable", name)) as f:
            assert "the reference diverged on 1 of 1 run(s)" in f.read(), name


def test_the_reference_figures_are_in_the_metrics_units(folder):
    r = results(folder, "short_vs_whole")
    (output,) = r["final_validation"]["reference"]["outputs"]
    (metric,) = [m for m in r["final_validation"]["metrics"] if m["output"] == output["output"]]
    assert output["unit"] == metric.get("unit", output["unit"])
    assert output["final_mae"] == pytest.approx(metric["mae"], rel=0.05)


def test_simulate_does_not_need_the_reference_yet(folder):
    """The records are simulated before any run: a reference not made yet is no refusal."""
    with open(os.path.join(SOURCE, "configs", "design_cargo.yaml")) as f:
        text = f.read()
    assert "final_validation" not in text
    write(folder, "simulated.yaml",
          text + "\nfinal_validation: {experiments: [zigzag_10], reference: not_made_yet}\n")
    status = subprocess.run([BINARY, "simulate", os.path.join(folder, "simulated.yaml"), "--out",
                             os.path.join(folder, "simulated")], capture_output=True, text=True)
    assert status.returncode == 0, status.stderr
    status = run(folder, "simulated.yaml", "simulated_run")  # the run needs it
    assert status.returncode != 0 and "final_validation.reference" in status.stderr
