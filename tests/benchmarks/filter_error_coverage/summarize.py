import json, sys, glob, os, numpy as np
import ship as S
PARS = ["a1", "a0", "b", "T3"]
def summ(fn):
    name = os.path.basename(fn).split("_")[0]
    tr = S.truth(S.SHIPS[name])
    rows = [json.loads(l) for l in open(fn)]
    out = []
    for p in PARS:
        v = np.array([r[p][0] for r in rows]); se = np.array([r[p][1] for r in rows])
        seh = np.array([r[p][2] if r[p][2] is not None else r[p][1] for r in rows])
        z = (v - tr[p]) / se
        cov = np.mean(np.abs(z) < 1.96)
        covh = np.mean(np.abs((v - tr[p]) / seh) < 1.96)
        out.append(f"{p}: cov {100*cov:3.0f}% (hess {100*covh:3.0f}%) bias {np.mean(z):+.2f}SE sd(z) {np.std(z, ddof=1):.2f} relbias {100*np.mean(v/tr[p]-1):+.2f}% relSD {100*np.std(v/tr[p],ddof=1):.2f}% SD/meanSE {np.std(v,ddof=1)/np.mean(se):.2f} bias/SD {np.mean(v-tr[p])/np.std(v,ddof=1):+.2f}")
    meth = {}
    for r in rows: meth[r["method"]] = meth.get(r["method"], 0) + 1
    return f"{os.path.basename(fn)[:-6]} n={len(rows)} {meth}\n   " + "\n   ".join(out)
for fn in sorted(sys.argv[1:] or glob.glob(os.path.join(os.environ.get("VESSELID_COVERAGE_DIR", "/tmp/vesselid_coverage"), "results", "*.jsonl"))):
    print(summ(fn))
