"""Identify a Nomoto steering model from pandas DataFrames, then predict a new manoeuvre.

Run after README command 2 (from the repository's root):
  build/vesselid simulate configs/nomoto_tanker.yaml --out out/tanker
  PYTHONPATH=build/python /usr/bin/python3 examples/python/identify_from_frames.py out/tanker
"""
import sys

import pandas as pd

import vesselid

folder = sys.argv[1] if len(sys.argv) > 1 else "out/tanker"
training, held_out = ["zz10s_a", "zz20s_a", "zz35p_a"], ["zz20s_b"]
frames = {n: pd.read_csv(f"{folder}/{n}.csv", float_precision="round_trip")
          for n in training + held_out}

config = vesselid.load_config("configs/nomoto_tanker.yaml")
del config["simulation"]
config["experiments"] = [e for e in config["experiments"] if e["name"] in frames]
for experiment in config["experiments"]:
    experiment.pop("file")  # the records come as frames
config["sets"] = {"training": training, "held_out": held_out}

result = vesselid.run(config, data=frames)
print("verdict:", result.verdict)
print(result.parameters[["value", "std_error", "unit", "role"]].to_string())
fits = result.fits
print(fits[fits["role"] == "validation"][["stage", "experiment", "output", "fit_percent"]]
      .to_string(index=False))
for finding in result.find(severity="warning"):
    print("warning:", finding.message)
