"""Plan the next manoeuvre from a fit: the cargo ship's second-order Nomoto model identified
from a short noisy 10/10 zigzag, then the rudder sequence of a 20/20 zigzag's duration that
shrinks its standard errors most (configs/design_cargo.yaml's design section), against the
standard alternatives.

Run after README command 2 (from the repository's root):
  PYTHONPATH=build/python /usr/bin/python3 examples/python/plan_next_experiment.py out/plan
"""
import sys

import vesselid

out = sys.argv[1] if len(sys.argv) > 1 else "out/plan"
config = vesselid.load_config("configs/design_cargo.yaml")
records = vesselid.simulate("configs/design_cargo.yaml")  # {file stem: DataFrame}
data = {"zigzag_10": records["cargo_zigzag_10"]}  # the short noisy zigzag
for experiment in config["experiments"]:
    experiment.pop("file")
vesselid.run(config, data=data, out=f"{out}/run", report=False)

plan = vesselid.design(config, f"{out}/run", out=f"{out}/design")
print(plan["text"])
widest = plan["widest"]["parameter"]
print(f"{widest} shrinks {plan['widest']['shrink']['planned']:.1f}x with the plan, "
      f"{plan['widest']['shrink']['zigzag_20_20']:.1f}x with a 20/20 zigzag")
print(plan["planned"].head())  # t, delta_deg: for the autopilot script
