"""The corpus judged by the parameters against the truth (issue rule, written before any
verdict was read): a run is GOOD when T and K each lie within max(5 %, 3 reported SE) of the
simulator's value with an SE of at most 50 % of the estimate, BAD otherwise; a GOOD run called
doubtful or failed is a false alarm, a BAD run called good a miss. For a wrong structure the
truth is the simulator's T and K (its defect aside)."""
import json,os
os.chdir(os.environ.get("VESSELID_GUST_DIR", "/tmp/vesselid_gust_corpus"))
C=json.load(open("cases.json"))
for c in C:
    r=json.load(open(f"cases/{c['name']}/out/results.json")); s=r["stages"][-1]
    row=[]; good=True
    for e in s["estimates"]:
        if e["name"] in ("T","K"):
            tr=c[e["name"]]; se=e["std_error"] or float('nan')
            ok = abs(e["value"]-tr) <= max(0.05*abs(tr), 3*se) and se<=0.5*abs(e["value"])
            good = good and ok
            row.append(f"{e['name']}={e['value']:.3g}±{se:.2g}({(e['value']-tr)/se:+.1f}SE){'' if ok else '!'}")
    kinds=sorted(set(f["kind"] for st in r["stages"] for f in st["findings"] if f["severity"]!="info") )
    print(f"{c['name']:11s} {'GOOD' if good else 'BAD ':4s} {r['verdict']:9s}", *row, kinds)

good = bad = fa = miss = 0
for c in C:
    r = json.load(open(f"cases/{c['name']}/out/results.json")); s = r["stages"][-1]
    ok = True
    for e in s["estimates"]:
        if e["name"] in ("T", "K"):
            tr = c[e["name"]]; se = e["std_error"] or float("nan")
            ok = ok and abs(e["value"] - tr) <= max(0.05 * abs(tr), 3 * se) and se <= 0.5 * abs(e["value"])
    if ok:
        good += 1; fa += r["verdict"] != "good"
    else:
        bad += 1; miss += r["verdict"] == "good"
print(f"GOOD {good}: false alarms {fa}; BAD {bad}: misses {miss}")
