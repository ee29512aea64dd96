"""Interval coverage per noise class, ship and parameter: the share of replicates whose 95 %
interval (estimate +- 1.96 SE) holds the truth, with its binomial 95 % range, the mean and SD
of (estimate - truth)/SE, and the verdicts. Reads every runs.jsonl under the folders given
(default $VESSELID_CORPUS_DIR), config B (noise: auto) unless another letter is given.
    python3 coverage.py [dir ...] [--config B]"""
import collections, glob, json, math, os, sys
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "filter_error_coverage"))
import ship as S  # the two hulls, shared with the coverage harness

PARS = ["a1", "a0", "b", "T3"]
CLS = {0: "white heading noise", 1: "AR(1) heading-sensor noise", 2: "wave-frequency yaw",
       3: "yaw-moment gusts", 4: "gyro drift", 5: "low log rate"}
args = [a for a in sys.argv[1:] if not a.startswith("--")]
key = sys.argv[sys.argv.index("--config") + 1] if "--config" in sys.argv else "B"
args = [a for a in args if a != key]
dirs = args or [os.environ.get("VESSELID_CORPUS_DIR", "/tmp/vesselid_noise_corpus")]
recs = []
for d in dirs:
    for f in glob.glob(os.path.join(d, "results", "runs.jsonl")):
        recs += [json.loads(l) for l in open(f)]

def wilson(k, n):
    if n == 0: return (math.nan, math.nan)
    p, z = k / n, 1.96
    c = (p + z * z / (2 * n)) / (1 + z * z / n)
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return 100 * (c - h), 100 * (c + h)

print(f"| class | ship | n | " + " | ".join(f"{p} cover % (95 % range) | {p} mean z (SD)" for p in PARS) + " | verdicts good/doubtful/failed |")
print("|---|---|---|" + "---|---|" * len(PARS) + "---|")
by = collections.defaultdict(list)
for r in recs:
    if key in r and r[key].get("est"): by[(r["cls"], r["ship"])].append(r)
for (c, name) in sorted(by):
    rs = by[(c, name)]
    tr = S.truth(S.SHIPS[name])
    cells = []
    for p in PARS:
        z = np.array([(r[key]["est"][p][0] - tr[p]) / r[key]["est"][p][1] for r in rs])
        k = int(np.sum(np.abs(z) <= 1.96)); lo, hi = wilson(k, len(z))
        cells += [f"{100 * k / len(z):.0f} ({lo:.0f}-{hi:.0f})", f"{z.mean():+.2f} ({z.std():.2f})"]
    v = collections.Counter(r[key]["verdict"] for r in rs)
    print(f"| {c} {CLS.get(c, '')} | {name} | {len(rs)} | " + " | ".join(cells) +
          f" | {v['good']}/{v['doubtful']}/{v['failed']} |")
