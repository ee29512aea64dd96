#!/usr/bin/python3
# A simulator outside the engine: first-order Nomoto (+defects) with yaw-rate gusts (Euler-Maruyama, dt=0.01)
import numpy as np, json, os, sys, math
# Cases and their records go to $VESSELID_GUST_DIR (default /tmp/vesselid_gust_corpus).
ROOT = os.environ.get("VESSELID_GUST_DIR", "/tmp/vesselid_gust_corpus")
D = math.radians
def simulate(c):
    rng = np.random.default_rng(c["seed"])
    dt = 0.01; L = c["len"]; n = int(round(L/dt)) + 1
    T, K, q = c["T"], c["K"], c["q"]
    fs = c["fs"]; sd = D(c["sd_deg"])
    defect = c.get("defect", "none"); p = c.get("p", {})
    # commanded rudder
    t = np.arange(n)*dt
    if c["input"] == "ms":
        amp = D(c.get("amp", 15)); per = [200, 97, 53, 31, 19]
        ph = rng.uniform(0, 2*np.pi, len(per))
        dc = sum(np.sin(2*np.pi*t/P + f) for P, f in zip(per, ph)); dc *= amp/np.max(np.abs(dc))
    else:
        dc = np.zeros(n)
    zz = c["input"] == "zz"; zamp = D(c.get("amp", 10)); rate = D(2.3)
    tgt = zamp; dcmd = 0.0
    psi, r, r2 = 0.0, 0.0, 0.0; de = 0.0; bl = 0.0
    PS = np.zeros(n); DL = np.zeros(n)
    sq = math.sqrt(q*dt); w = rng.standard_normal(n)
    for i in range(n):
        if zz:
            if tgt > 0 and psi >= zamp: tgt = -zamp
            elif tgt < 0 and psi <= -zamp: tgt = zamp
            dcmd += max(-rate*dt, min(rate*dt, tgt - dcmd)); d = dcmd
        else:
            d = dc[i]
        DL[i] = d; PS[i] = psi
        # effective rudder
        if defect == "deadband":
            db = D(p["db"]); de = math.copysign(max(abs(d)-db, 0.0), d)
        elif defect == "ratelimit":
            rl = D(p["rate"])*dt; de += max(-rl, min(rl, d - de))
        elif defect == "backlash":
            b = D(p["b"])/2
            if d > bl + b: bl = d - b
            elif d < bl - b: bl = d + b
            de = bl
        elif defect == "bias":
            de = d + D(p["bias"])
        else:
            de = d
        Ti, Ki = T, K
        if defect == "speed" and t[i] > p["at"]:
            Ti, Ki = T/p["ratio"], K*p["ratio"]
        if defect == "second":
            # T1T2 r'' + (T1+T2) r' + r = K(de + T3 de'); states r, x with de' approximated via state form
            T1, T2, T3 = p["T1"], p["T2"], p["T3"]
            # state form: r = x1 + (K*T3/(T1*T2))*... use controllable form on transfer K(1+T3 s)/((1+T1 s)(1+T2 s))
            a1 = (T1+T2)/(T1*T2); a0 = 1/(T1*T2); b1 = K*T3/(T1*T2); b0 = K/(T1*T2)
            # x1' = x2, x2' = -a0 x1 - a1 x2 + de ; r = b0 x1 + b1 x2
            x1, x2 = r, r2
            x1n = x1 + dt*x2; x2n = x2 + dt*(-a0*x1 - a1*x2 + de)
            r, r2 = x1n, x2n
            ry = b0*x1 + b1*x2
            # gust on r directly: add to output-rate through extra integrator
            psi += dt*ry + (c.get("gpsi", 0.0))
            # gust: additional first-order gust-rate state g' = -g/T + w
            r2 += 0.0
            c.setdefault("_g", 0.0)
            c["_g"] += dt*(-c["_g"]/T) + sq*w[i]
            psi += dt*c["_g"]
            continue
        n3 = p.get("n3", 0.0) if defect == "cubic" else 0.0
        rn = r + dt*(Ki*de - r - n3*r**3)/Ti + sq*w[i]
        psi += dt*r; r = rn
    step = int(round(1/(fs*dt)))
    idx = np.arange(0, n, step)
    y = PS[idx] + sd*rng.standard_normal(len(idx))
    return t[idx], DL[idx], y, PS[idx]

CFG = """model: {family: nomoto, type: first_order}
experiments:
  - {name: a, file: a.csv, inputs: {delta: delta}, outputs: {psi: psi}}
stages:
  - name: fe
    parameters:
      T: {start: 15, lower: 1, upper: 200}
      K: {start: 0.05, lower: 0.001, upper: 2}
    noise: %s
"""
if __name__ == "__main__":
    c = json.loads(sys.argv[1]); name = c["name"]
    d = f"{ROOT}/cases/{name}"; os.makedirs(d + "/data", exist_ok=True)
    tt, dl, y, ptrue = simulate(dict(c))
    with open(d + "/data/a.csv", "w") as f:
        f.write("t,delta,psi\n")
        for a, b, e in zip(tt, dl, y): f.write("%.4f,%.10g,%.10g\n" % (a, b, e))
    noise = "{method: auto}" if c.get("auto") else "{method: filter_error, process: {r: auto}}"
    open(d + "/cfg.yaml", "w").write(CFG % noise)
    json.dump(c, open(d + "/case.json", "w"))
    print(name, "psi range deg %.1f..%.1f" % (np.degrees(ptrue.min()), np.degrees(ptrue.max())))
