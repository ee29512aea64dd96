#!/bin/bash
# The filter-error method on real records (docs/models.md, "Real records"): the MARIN KVLCC2
# free-running tests and the Otter USV field logs of LSJohnsen/Otter-USV, each fitted by output
# error and by `noise: {method: auto}`. The records are read, never committed: the KVLCC2 files
# from $VESSELID_KVLCC2_DIR (default ../shared/data/kvlcc2/kvlcc2), the Otter logs from a git
# mirror of LSJohnsen/Otter-USV at $VESSELID_OTTER_GIT. Outputs go to $VESSELID_REAL_DIR.
#
#   VESSELID_OTTER_GIT=/path/to/Otter-USV.git tests/benchmarks/real_noise/run.sh
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
V=$(readlink -f "${VESSELID_BINARY:-build/vesselid}")
OUT=${VESSELID_REAL_DIR:-/tmp/vesselid_real_noise}
KVLCC2=$(readlink -f "${VESSELID_KVLCC2_DIR:-../shared/data/kvlcc2/kvlcc2}")
mkdir -p "$OUT/kvlcc2" "$OUT/otter/raw"
cd "$OUT/kvlcc2"
VESSELID_KVLCC2_DIR="$KVLCC2" python3 "$HERE/kvlcc2/convert.py"
for f in kvlcc2_oe kvlcc2_auto kvlcc2_n1_oe kvlcc2_n1_auto; do
  /usr/bin/time -f 'WALL %e s' "$V" run "$HERE/kvlcc2/$f.yaml" --data . --out "out_${f#kvlcc2_}" \
    > "run_${f#kvlcc2_}.log" 2>&1 || echo "$f: exit $?"
done
if [ -n "${VESSELID_OTTER_GIT:-}" ]; then
  cd "$OUT/otter"
  for r in 12-27-203 12-44-083 12-50-003 12-55-233 16-07-363fast2meterpersekundr55; do
    git --git-dir="$VESSELID_OTTER_GIT" show "HEAD:Otter API/logs/2024-04-23_$r.csv" > "raw/2024-04-23_$r.csv"
  done
  python3 "$HERE/otter/convert.py" raw
  for f in otter_oe otter_auto otter_r_oe otter_r_auto; do
    /usr/bin/time -f 'WALL %e s' "$V" run "$HERE/otter/$f.yaml" --data . --out "out_${f#otter_}" \
      > "run_${f#otter_}.log" 2>&1 || echo "$f: exit $?"
  done
fi
python3 "$HERE/summarize.py" "$OUT"/kvlcc2/out_* "$OUT"/otter/out_* 2>/dev/null || true
