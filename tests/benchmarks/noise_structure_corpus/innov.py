import os
import json, re, collections, math
ROOT = os.environ.get("VESSELID_CORPUS_DIR", "/tmp/vesselid_noise_corpus")
recs = [json.loads(l) for l in open(os.path.join(ROOT, "results", "runs.jsonl"))]
by = collections.defaultdict(list)
for r in recs:
    b = r["B"]
    notes = b.get("notes") or []
    stat = [ (float(m.group(1)), int(m.group(2)), float(m.group(3))) for n in notes for m in [re.search(r"innovation structure: .*N R\^2 ([0-9.e+-]+) on (\d+) functions.*\(p ([0-9.e+-]+|nan)\)", n)] if m]
    chosen = b.get("auto_note")
    kept = chosen is not None and "output error kept" in chosen
    by[r["cls"]].append((r["ship"], r["seed"], b["label"], b["verdict"], stat[0] if stat else None, kept, sorted(f for f in b["findings"] if "warning" in f or "failure" in f)))
for c in sorted(by):
    print("class", c)
    for row in by[c]:
        s = row[4]
        print("  %-7s %d %-4s %-9s %s %s" % (row[0], row[1], row[2], row[3], ("NR2 %8.1f m %d p %.1e" % s) if s else "no test (OE kept)" if row[5] else "no test", ",".join(row[6])))
