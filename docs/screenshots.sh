#!/usr/bin/env bash
# Renders the pages of a tpf report in headless Chromium (Debian package `chromium`) as a reader
# sees them: one PNG per page, 1400 px wide, the first screen (900 px) unless --height says more.
#
#   docs/screenshots.sh [--height PX] REPORT_DIR OUT_DIR
#
# e.g. after the demo: docs/screenshots.sh build/release/demo /tmp/shots; docs/img/report.png is
# /tmp/shots/index.png. The pages are self-contained: no network is needed or used.
set -euo pipefail

height=900
if [[ ${1:-} == --height ]]; then
  height=$2
  shift 2
fi
if [[ $# -ne 2 ]]; then
  echo "usage: $0 [--height PX] REPORT_DIR OUT_DIR" >&2
  exit 2
fi
report=$(cd "$1" && pwd)
mkdir -p "$2"
out=$(cd "$2" && pwd)

browser=$(command -v chromium || command -v chromium-browser || true)
if [[ -z $browser ]]; then
  echo "$0: no chromium found (Debian: apt-get install chromium)" >&2
  exit 1
fi
shopt -s nullglob
pages=("$report"/*.html)
if [[ ${#pages[@]} -eq 0 ]]; then
  echo "$0: no .html page in $report" >&2
  exit 1
fi
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
for page in "${pages[@]}"; do
  png="$out/$(basename "$page" .html).png"
  # --no-sandbox: Chromium refuses to start as root otherwise (containers, CI).
  "$browser" --headless=new --no-sandbox --disable-gpu --hide-scrollbars --no-first-run \
    --user-data-dir="$profile" --window-size="1400,$height" --screenshot="$png" \
    "file://$page" >/dev/null 2>&1
  [[ -s $png ]] || { echo "$0: Chromium wrote no $png" >&2; exit 1; }
  echo "$png"
done
