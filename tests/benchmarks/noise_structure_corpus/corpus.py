"""Labelled corpus: usage corpus.py <class> <ship> <seed> [configs=ABC]. Appends to results/runs.jsonl"""
import json, math, os, subprocess, sys, shutil, time
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "filter_error_coverage"))
import ship as S  # the two hulls, shared with the coverage harness
import sim

VES = os.path.abspath(os.environ.get("VESSELID_BINARY", "build/vesselid"))
ROOT = os.environ.get("VESSELID_CORPUS_DIR", "/tmp/vesselid_noise_corpus")
PARS = ["a1", "a0", "b", "T3"]
D2R = math.pi / 180
Q_YAW = {"patrol": 4.5e-8, "supply": 7e-7}   # -> ~0.5 deg RMS heading deviation (cal.py)
# A: output error alone; B: auto asked for; C: the full model given; E: no noise key (the default)
CFG_NOISE = {"A": "output_error", "B": "{method: auto}", "E": None,
             "C": "{method: filter_error, measurement: {psi: {type: ar1, white: true}}, process: {eta2: auto}}"}

_fine = {}
def fine(name, **kw):
    key = (name, tuple(sorted(kw.items())))
    if key not in _fine:
        t, D, P, R, DE = sim.simulate(name, **kw)
        _fine[key] = (t, D, P)
    return _fine[key]

def make_data(cls, name, seed):
    sh = S.SHIPS[name]
    rng = np.random.default_rng(100000 * cls + 1000 * seed + (0 if name == "patrol" else 7))
    rate = sh["rate"]; white = 0.1; info = {}
    kw = {}
    if cls == 3: kw = dict(q_yaw=Q_YAW[name], seed=int(rng.integers(1 << 30))); info["q_yaw"] = Q_YAW[name]
    if cls == 6: kw = dict(backlash=2.0 if seed % 2 else 1.0)
    if cls == 7: kw = dict(deadzone=2.5)
    if cls == 8: kw = dict(ratelim=2.3 if seed % 2 else 5.0)
    if cls == 9:
        A, B, C = S.state_space(sh); tt, DD, PP, RR, _ = sim.simulate(name)
        rmax = np.max(np.abs(RR)) / C[1]
        kw = dict(nrrr=(1.0 if seed % 2 else 0.3) * abs(A[1, 1]) / rmax ** 2)
    info.update(kw)
    if cls == 5: rate = 0.5 if seed % 2 else 1.0
    if cls == 1: white = 0.05
    t, d, p = fine(name, **kw)
    h = t[1] - t[0]
    iy = np.arange(0, len(t), int(round(1 / rate / h)))
    ts = t[iy]; dt = 1 / rate; n = len(iy)
    y = p[iy] + rng.standard_normal(n) * white * D2R
    if cls == 1:
        tau = rng.uniform(0.5, 4); sd = rng.uniform(0.1, 0.15); a = math.exp(-dt / tau)
        z = np.zeros(n); z[0] = rng.standard_normal() * sd
        e = rng.standard_normal(n) * sd * math.sqrt(1 - a * a)
        for k in range(1, n): z[k] = a * z[k - 1] + e[k]
        y += z * D2R; info.update(tau=tau, sd=sd)
    if cls == 2:
        om = rng.uniform(0.6, 1.0); ze = rng.uniform(0.05, 0.2); sd = rng.uniform(0.2, 0.5)
        # exact discretisation of z1'=z2, z2'=-om^2 z1-2 ze om z2 + w (white), on the 0.01 s grid
        from scipy.linalg import expm
        Ac = np.array([[0, 1], [-om * om, -2 * ze * om]]); hh = 0.01
        Phi = expm(Ac * hh)
        # Van Loan for Q with unit intensity
        M = np.block([[-Ac, np.diag([0, 1.0])], [np.zeros((2, 2)), Ac.T]]) * hh
        E = expm(M); Q = E[2:, 2:].T @ E[:2, 2:]
        L = np.linalg.cholesky(Q + 1e-30 * np.eye(2))
        m = len(t); W = rng.standard_normal((m, 2)) @ L.T
        Z = np.zeros((m, 2)); zz = np.zeros(2)
        burn = 2000
        for k in range(burn): zz = Phi @ zz + L @ rng.standard_normal(2)
        p00, p01, p10, p11 = Phi.ravel(); z1, z2 = zz
        for k in range(m):
            Z[k, 0] = z1
            z1, z2 = p00 * z1 + p01 * z2 + W[k, 0], p10 * z1 + p11 * z2 + W[k, 1]
        wv = Z[iy, 0]; wv *= sd / np.std(wv)
        y += wv * D2R; info.update(omega=om, zeta=ze, sd=sd)
    if cls == 4:
        bias = np.cumsum(rng.standard_normal(n)) * (0.3 / math.sqrt(n))
        y += bias * D2R; info.update(drift_end=float(bias[-1]))
    if cls == 5: info["rate"] = rate
    return ts, d[iy], y, info

def config(name, tr, noise, csv="data.csv"):
    exp = ["  - name: ms", f"    file: {csv}", "    inputs: {delta: delta}", "    outputs: {psi: psi}"]
    st = ["  - name: oe", "    parameters:"]
    bounds = dict(a1=(1e-3, 10.0), a0=(-1.0, 1.0), b=(-1.0, 1.0), T3=(0.0, 100.0))
    for p in PARS:
        lo, hi = bounds[p]
        st.append(f"      {p}: {{start: {tr[p]*1.05:.10g}, lower: {lo}, upper: {hi}}}")
    st.append("    free_initial_states: [psi]")
    if noise: st.append(f"    noise: {noise}")
    return "\n".join(["model: {family: nomoto, type: second_order_rates}", "experiments:"] + exp +
                     ["stages:"] + st) + "\n"

def label(est, tr):
    if est is None: return "bad", ["no estimates"]
    why = []
    for p in PARS:
        if p not in est: why.append(p + " missing"); continue
        v, se = est[p][0], est[p][1]
        if se is None or not np.isfinite(se): why.append(p + " SE missing"); continue
        if abs(v - tr[p]) > max(0.05 * abs(tr[p]), 3 * se): why.append(p + " off")
        if se > 0.5 * abs(v): why.append(p + " SE>50%")
    return ("good" if not why else "bad"), why

def run_cfg(wd, name, tr, key):
    cd = f"{wd}/{key}"; shutil.rmtree(cd, ignore_errors=True); os.makedirs(cd)
    open(f"{cd}/cfg.yaml", "w").write(config(name, tr, CFG_NOISE[key], "data.csv"))
    t0 = time.time()
    r = subprocess.run([VES, "run", "cfg.yaml", "--data", "..", "--out", "out", "--quiet", "--no-report"],
                       cwd=cd, capture_output=True, text=True)
    o = {"rc": r.returncode, "wall": round(time.time() - t0, 2)}
    if not os.path.exists(f"{cd}/out/results.json"):
        o.update(verdict="NO_RESULTS", stderr=r.stderr[-1500:], label="bad", why=["no results"]); return o
    res = json.load(open(f"{cd}/out/results.json"))
    o["verdict"] = res.get("verdict")
    stage = res["stages"][-1]
    o["stage_verdict"] = stage.get("verdict")
    est = {}
    for e in stage.get("estimates", []):
        if e["name"] in PARS: est[e["name"]] = (e["value"], e.get("std_error"))
    o["est"] = est or None
    o["label"], o["why"] = label(o["est"], tr)
    fk = []
    for f in (res.get("findings") or []) + (stage.get("findings") or []):
        fk.append(f"{f.get('kind')}:{f.get('severity')}")
    o["findings"] = sorted(set(fk))
    o["notes"] = stage.get("notes")
    o["unc_method"] = (stage.get("uncertainty") or {}).get("method")
    o["noise_est"] = [(e["name"], e["value"], e.get("std_error")) for e in stage.get("estimates", []) if e.get("kind") == "noise"]
    dm = [f.get("message") for f in stage.get("findings") or [] if f.get("kind") == "disturbance_model"]
    o["disturbance_msg"] = dm[0] if dm else None
    chosen = [n for n in (stage.get("notes") or []) if "noise auto" in n]
    o["auto_note"] = chosen[0] if chosen else None
    if r.stderr.strip(): o["stderr"] = r.stderr[-800:]
    shutil.rmtree(f"{cd}/out/traces", ignore_errors=True)
    return o

def run(cls, name, seed, keys="ABC"):
    tr = S.truth(S.SHIPS[name])
    wd = f"{ROOT}/runs/c{cls}_{name}_{seed}"; os.makedirs(wd, exist_ok=True)
    ts, d, y, info = make_data(cls, name, seed)
    with open(f"{wd}/data.csv", "w") as f:
        f.write("t,delta,psi\n")
        for a, b, c in zip(ts, d, y): f.write("%.4f,%.10g,%.10g\n" % (a, b, c))
    rec = {"cls": cls, "ship": name, "seed": seed, "info": info}
    for k in keys: rec[k] = run_cfg(wd, name, tr, k)
    return rec

if __name__ == "__main__":
    cls, name, seed = int(sys.argv[1]), sys.argv[2], int(sys.argv[3])
    keys = sys.argv[4] if len(sys.argv) > 4 else "ABC"
    rec = run(cls, name, seed, keys)
    os.makedirs(f"{ROOT}/results", exist_ok=True)
    with open(f"{ROOT}/results/runs.jsonl", "a") as f: f.write(json.dumps(rec) + "\n")
    print(cls, name, seed, {k: (rec[k]["label"], rec[k]["verdict"], rec[k]["wall"]) for k in keys})
