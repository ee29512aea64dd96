import json, re, glob, os
os.chdir(os.environ.get("VESSELID_GUST_DIR", "/tmp/vesselid_gust_corpus"))
C = json.load(open("cases.json"))
for c in C:
    n = c["name"]; p = f"cases/{n}/out/results.json"
    if not os.path.exists(p): print(n, "NO RESULT", open(f"cases/{n}/engine.log").read()[-200:]); continue
    r = json.load(open(p)); s = r["stages"][-1]
    kinds = [f["kind"] for st in r["stages"] for f in st["findings"]] + [f["kind"] for f in r["findings"]]
    fr = [f["message"] for st in r["stages"] for f in st["findings"] if f["kind"] == "free_run_drift"]
    ratio = re.findall(r"ratio of sums of squares ([0-9.e+-]+)", fr[0]) if fr else []
    fitm = re.findall(r"fit (-?[0-9.]+) %", fr[0]) if fr else []
    nr2 = [re.findall(r"N R\^2 ([0-9.]+).*?\(p ([0-9.e-]+)\)", x) for x in s["notes"] if "innovation structure" in x]
    est = {e["name"]: e["value"] for e in s["estimates"] if e["name"] in ("T", "K", "q.process.r")}
    dis = [x for x in s["notes"] if x.startswith("filter-error method")]
    lab = "correct" if n.startswith("c") else "wrong"
    flags = sorted(set(k for k in kinds if k not in ("disturbance_model",)))
    print(f"{n:11s} {lab:7s} {r['verdict']:9s} frd={'Y' if fr else '-'} ratio={','.join(ratio) or '-':6s} fit={','.join(fitm) or '-':7s} "
          f"DAS={'Y' if 'disturbance_absorbs_structure' in kinds else '-'} NR2={nr2[0] if nr2 else '-'} "
          f"T={est.get('T',0):.1f}/{c['T']} K={est.get('K',0):.3f}/{c['K']} q={est.get('q.process.r',float('nan')):.1e}/{c['q']:.0e} {flags} {dis[0][22:60] if dis else ''}")
