#!/bin/bash
# Every case of cases.py simulated by sim.py and run by the engine, one process at a time;
# then summ.py prints a row per case. VESSELID_BINARY: the engine (default build/vesselid of
# this checkout); VESSELID_GUST_DIR: the scratch folder (default /tmp/vesselid_gust_corpus).
set -e
here=$(cd "$(dirname "$0")" && pwd)
export VESSELID_GUST_DIR=${VESSELID_GUST_DIR:-/tmp/vesselid_gust_corpus}
binary=$(realpath "${VESSELID_BINARY:-$here/../../../build/vesselid}")
/usr/bin/python3 "$here/cases.py" > /dev/null
/usr/bin/python3 -c "import json,os;[print(json.dumps(c)) for c in json.load(open(os.path.join(os.environ['VESSELID_GUST_DIR'],'cases.json')))]" |
while read -r line; do
  /usr/bin/python3 "$here/sim.py" "$line" > /dev/null
  name=$(echo "$line" | /usr/bin/python3 -c "import json,sys;print(json.load(sys.stdin)['name'])")
  (cd "$VESSELID_GUST_DIR/cases/$name" && rm -rf out &&
   "$binary" run cfg.yaml --data data --out out --quiet --no-report > engine.log 2>&1 || true)
done
/usr/bin/python3 "$here/summ.py"
