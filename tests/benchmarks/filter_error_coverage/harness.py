"""Replicates: noise-free fine trajectory (cached) -> sampled + noisy CSV -> vesselid run -> estimates.
usage: harness.py <ship> <variant> <n_reps> [first_seed]
Variants are defined in VARIANTS below (one change at a time from 'base')."""
import json, os, subprocess, sys, shutil
import numpy as np
import ship as S

HERE = os.path.dirname(os.path.abspath(__file__))
# The engine (VESSELID_BINARY, else build/vesselid of this checkout) and a scratch folder for the
# replicates' records, runs and results (VESSELID_COVERAGE_DIR, else /tmp/vesselid_coverage).
VES = os.environ.get("VESSELID_BINARY", os.path.join(HERE, "..", "..", "..", "build", "vesselid"))
ROOT = os.environ.get("VESSELID_COVERAGE_DIR", "/tmp/vesselid_coverage")
PARS = ["a1", "a0", "b", "T3"]

def fine(name):
    f = f"{ROOT}/fine_{name}.npz"
    if not os.path.exists(f):
        t, d, p, r, c = S.simulate(S.SHIPS[name])
        np.savez(f, t=t, d=d, p=p, r=r, c=c)
    z = np.load(f)
    return z["t"], z["d"], z["p"]

# each variant: dict of overrides
VARIANTS = {
    "base": {},
    "no_rudder_noise": dict(rudder_sd=0.0),
    "heading_noise_only": dict(rudder_sd=0.0),             # same as above (heading noise stays)
    "no_noise_at_all": dict(rudder_sd=0.0, heading_sd=0.0),
    "rudder_fast_exact": dict(rudder_sd=0.0, rudder_rate=100.0),  # exact rudder logged at 100 Hz
    "rudder_fast_noisy": dict(rudder_rate=100.0, rudder_sd_fast=True),  # noisy rudder at 100 Hz, same noise/sample
    "cubic": dict(interp="cubic"),
    "cubic_exact": dict(rudder_sd=0.0, interp="cubic"),
    "zoh_exact": dict(rudder_sd=0.0, interp="zero_order_hold"),
    "hessian": dict(unc="{method: hessian, input_noise: off}"),
    "hac": dict(unc="{method: sandwich_hac, input_noise: off}"),
    "latent": dict(latent=True),
    "latent_cubic": dict(latent=True, interp="cubic"),
    "max_step_fine": dict(max_step=0.01),
    "max_step_fine_exact": dict(max_step=0.01, rudder_sd=0.0),
    "free_psi0": dict(free_psi0=True),
    "free_psi0_exact": dict(free_psi0=True, rudder_sd=0.0),
    "fp_fast_noisy": dict(free_psi0=True, rudder_rate=100.0),
    "fp_fast_exact": dict(free_psi0=True, rudder_rate=100.0, rudder_sd=0.0),
    "fp_latent": dict(free_psi0=True, latent=True),
    "fp_latent_sigma": dict(free_psi0=True, latent="{delta: {sigma: %.10g}}" % (0.05 * 3.141592653589793 / 180)),
    "fp_hessian": dict(free_psi0=True, unc="{method: hessian, input_noise: off}"),
    "fp_zoh": dict(free_psi0=True, interp="zero_order_hold"),
    "fp_cubic": dict(free_psi0=True, interp="cubic"),
    "fp_max_step": dict(free_psi0=True, max_step=0.01),
    "fp_rudder_noise_only": dict(free_psi0=True, heading_sd=0.0),
    "fp_no_noise": dict(free_psi0=True, heading_sd=0.0, rudder_sd=0.0),
    "fe_white": dict(noise="{method: filter_error}"),
    "fe_process": dict(noise="{method: filter_error, process: {eta2: auto}}"),
    "fe_auto": dict(noise="{method: auto}"),
}

def config(name, tr, v, csv):
    interp = v.get("interp")
    exp = [f"  - name: ms", f"    file: {csv}", "    inputs: {delta: delta}", "    outputs: {psi: psi}"]
    if interp: exp.append(f"    interpolation: {{delta: {interp}}}")
    if v.get("latent"): exp.append("    input_noise: " + (v["latent"] if isinstance(v["latent"], str) else "{delta: auto}"))
    st = ["  - name: oe", "    parameters:"]
    bounds = dict(a1=(1e-3, 10.0), a0=(-1.0, 1.0), b=(-1.0, 1.0), T3=(0.0, 100.0))
    for p in PARS:
        lo, hi = bounds[p]
        st.append(f"      {p}: {{start: {tr[p]*1.05:.10g}, lower: {lo}, upper: {hi}}}")
    if v.get("free_psi0"): st.append("    free_initial_states: [psi]")
    if v.get("max_step"): st.append(f"    integration: {{max_step: {v['max_step']}}}")
    if v.get("unc"): st.append(f"    uncertainty: {v['unc']}")
    if v.get("noise"): st.append(f"    noise: {v['noise']}")
    return "\n".join(["model: {family: nomoto, type: second_order_rates}", "experiments:"] + exp +
                     ["stages:"] + st) + "\n"

def replicate(name, vname, seed):
    v = VARIANTS[vname]
    sh = S.SHIPS[name]
    tr = S.truth(sh)
    t, d, p = fine(name)
    rng = np.random.default_rng(1000 * seed + (0 if name == "patrol" else 7))
    hsd = np.deg2rad(v.get("heading_sd", 0.1)); rsd = np.deg2rad(v.get("rudder_sd", 0.05))
    h = t[1] - t[0]
    step_y = int(round(1 / sh["rate"] / h))
    step_u = int(round(1 / v.get("rudder_rate", sh["rate"]) / h))
    iy = np.arange(0, len(t), step_y); iu = np.arange(0, len(t), step_u)
    # draw heading noise first so it is the same across variants for a seed
    ey = rng.standard_normal(len(iy)) * hsd
    eu = rng.standard_normal(len(iu)) * rsd
    rows = {}
    for k, i in enumerate(iu): rows.setdefault(i, [None, None])[0] = d[i] + eu[k]
    for k, i in enumerate(iy): rows.setdefault(i, [None, None])[1] = p[i] + ey[k]
    wd = f"{ROOT}/runs/{name}_{vname}_{seed}"
    shutil.rmtree(wd, ignore_errors=True); os.makedirs(wd)
    with open(f"{wd}/data.csv", "w") as f:
        f.write("t,delta,psi\n")
        for i in sorted(rows):
            a, b = rows[i]
            f.write("%.4f,%s,%s\n" % (t[i], "" if a is None else "%.10g" % a, "" if b is None else "%.10g" % b))
    open(f"{wd}/cfg.yaml", "w").write(config(name, tr, v, "data.csv"))
    r = subprocess.run([VES, "run", "cfg.yaml", "--data", ".", "--out", "out", "--quiet", "--no-report"],
                       cwd=wd, capture_output=True, text=True)
    if r.returncode not in (0, 3, 4) or not os.path.exists(f"{wd}/out/results.json"):
        print("FAILED", wd, r.returncode, r.stderr[-2000:]); return None
    res = json.load(open(f"{wd}/out/results.json"))
    out = {"seed": seed}
    stage = res["stages"][-1]
    for e in stage["estimates"] if "estimates" in stage else stage["parameters"]:
        if e["name"] in PARS:
            out[e["name"]] = (e["value"], e["std_error"], e.get("std_error_hessian"))
    out["method"] = stage.get("uncertainty", {}).get("method")
    shutil.rmtree(f"{wd}/out/traces", ignore_errors=True)
    return out

if __name__ == "__main__":
    name, vname, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
    first = int(sys.argv[4]) if len(sys.argv) > 4 else 1
    fn = f"{ROOT}/results/{name}_{vname}.jsonl"
    os.makedirs(f"{ROOT}/results", exist_ok=True)
    with open(fn, "a") as f:
        for s in range(first, first + n):
            o = replicate(name, vname, s)
            if o: f.write(json.dumps(o) + "\n"); f.flush()
