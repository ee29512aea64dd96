#!/bin/sh
# Screenshot of a run report (report.html) in headless Chromium, the top `height` pixels of
# the page at `width` pixels:
#
#   examples/report_screenshot.sh out/erunsal/report.html report.png [width] [height]
set -eu
if [ $# -lt 2 ]; then
  echo "usage: $0 DIR/report.html OUT.png [width] [height]" >&2
  exit 2
fi
report=$(realpath "$1")
png=$(realpath -m "$2")
width=${3:-1400}
height=${4:-3000}
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
  --disable-background-networking --disable-component-update --disable-sync \
  --user-data-dir="$profile" --virtual-time-budget=10000 --hide-scrollbars \
  --window-size="$width,$height" --screenshot="$png" "file://$report" 2>/dev/null
test -s "$png"
echo "$png"
