import os
import json, sys, collections, numpy as np
ROOT = os.environ.get("VESSELID_CORPUS_DIR", "/tmp/vesselid_noise_corpus")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "filter_error_coverage"))
import ship as S  # the two hulls, shared with the coverage harness
PARS = ["a1", "a0", "b", "T3"]
CLS = {0: "clean (control)", 1: "AR(1) sensor", 2: "wave yaw", 3: "gust process", 4: "gyro drift",
       5: "low log rate", 6: "backlash", 7: "dead band", 8: "rate limit", 9: "cubic damping"}
recs = [json.loads(l) for l in open(os.path.join(ROOT, "results", "runs.jsonl"))]
import os
if os.path.exists(os.path.join(ROOT, "results", "runs_D.jsonl")):
    dd = {(r["cls"], r["ship"], r["seed"]): r["D"] for r in map(json.loads, open(os.path.join(ROOT, "results", "runs_D.jsonl")))}
    for r in recs:
        k = (r["cls"], r["ship"], r["seed"])
        if k in dd: r["D"] = dd[k]
keys = [k for k in "ABCDE" if any(k in r for r in recs)]
def pct(a, b): return f"{a}/{b} ({100*a/b:.0f}%)" if b else "-"
print("## Verdict vs label per class and config (FA = good-labelled runs called doubtful/failed; miss = bad-labelled called good)")
print("| class | cfg | n | labels good/bad | verdicts g/d/f | false alarms | misses |")
print("|---|---|---|---|---|---|---|")
for c in sorted(CLS):
    rs = [r for r in recs if r["cls"] == c]
    if not rs: continue
    for k in keys:
        rr = [r[k] for r in rs if k in r]
        if not rr: continue
        g = [x for x in rr if x["label"] == "good"]; b = [x for x in rr if x["label"] == "bad"]
        fa = sum(x["verdict"] != "good" for x in g); mi = sum(x["verdict"] == "good" for x in b)
        vc = collections.Counter(x["verdict"] for x in rr)
        print(f"| {c} {CLS[c]} | {k} | {len(rr)} | {len(g)}/{len(b)} | {vc['good']}/{vc['doubtful']}/{vc['failed']}" +
              (f" +{len(rr)-vc['good']-vc['doubtful']-vc['failed']} other" if len(rr)-vc['good']-vc['doubtful']-vc['failed'] else "") +
              f" | {pct(fa, len(g))} | {pct(mi, len(b))} |")
print()
print("## mean |err|/SE over the 4 parameters, 95% coverage (|err|<1.96 SE), median |rel err| %")
print("| class | " + " | ".join(f"{k} mean z | {k} cov95 | {k} med rel% " for k in keys) + "|")
print("|---|" + "---|" * (3 * len(keys)))
for c in sorted(CLS):
    rs = [r for r in recs if r["cls"] == c]
    if not rs: continue
    row = []
    for k in keys:
        zs, re = [], []
        for r in rs:
            x = r.get(k)
            if not x or not x.get("est"): continue
            tr = S.truth(S.SHIPS[r["ship"]])
            for p in PARS:
                v, se = x["est"][p]
                zs.append(abs(v - tr[p]) / se); re.append(abs(v / tr[p] - 1) * 100)
        zs = np.array(zs)
        if not len(zs): row += ["", "", ""]; continue
        row += [f"{zs.mean():.2f}", f"{100*np.mean(zs<1.96):.0f}%", f"{np.median(re):.2f}"]
    print(f"| {c} {CLS[c]} | " + " | ".join(row) + " |")
print()
print("## B (noise auto) chosen candidate per class")
import re as _re
for c in sorted(CLS):
    rs = [r for r in recs if r["cls"] == c and "B" in r]
    ch = collections.Counter()
    for r in rs:
        n = r["B"].get("auto_note")
        if n is None: ch["(no auto note)"] += 1; continue
        if "output error kept" in n: ch["output_error kept (white residuals)"] += 1; continue
        m = _re.findall(r";\s*([^;:]*?) [-\d.]+ \(k \d+\) chosen", " ;" + n.split(":", 2)[-1])
        ch[m[0].strip() if m else "?"] += 1
    print(f"- {c} {CLS[c]}: " + ", ".join(f"{a} x{b}" for a, b in ch.most_common()))
print()
print("## findings kinds (count of runs) per class and config")
for c in sorted(CLS):
    rs = [r for r in recs if r["cls"] == c]
    for k in keys:
        fc = collections.Counter(f for r in rs if k in r for f in r[k].get("findings", []))
        print(f"- {c} {k}: " + ", ".join(f"{a} {b}" for a, b in sorted(fc.items())))
