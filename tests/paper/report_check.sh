#!/usr/bin/env bash
# The report in a real browser (issue 15): loads report.html from disk in headless Chromium and
# checks, by the page's own self-test (report.html?selftest), that every image loads, nothing is
# requested but files, no script error is raised, and the comparison view switches images; then
# looks for console errors in Chromium's log. With a second argument, also takes screenshots
# there (at 1280 and 1920 pixels wide, and of the comparison view). Skips (exit 77) without
# Chromium (Debian: apt-get install chromium).
# Usage: report_check.sh /path/to/radrecon [SCREENSHOT_DIR]
set -euo pipefail
RADRECON=${1:?usage: report_check.sh /path/to/radrecon [SCREENSHOT_DIR]}
SHOTS=${2:-}
CHROME=$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)
if [ -z "$CHROME" ]; then
  echo "report_check: skipped: no Chromium (apt-get install chromium)"
  exit 77
fi
OUT=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_report.XXXXXX")
trap 'rm -rf "$OUT"' EXIT
"$RADRECON" paper --out "$OUT/paper" --quiet
PAGE="file://$OUT/paper/report.html"
# No network: every host name resolves to nothing, so a request off the file would fail (and
# the self-test lists any resource that is not a file).
flags=(--headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run --disable-extensions
       --host-resolver-rules="MAP * ~NOTFOUND" --virtual-time-budget=10000 --enable-logging=stderr --v=0)
timeout 120 "$CHROME" "${flags[@]}" --dump-dom "$PAGE?selftest" > "$OUT/dom.html" 2> "$OUT/chrome.log"
verdict=$(grep -o 'SELFTEST [A-Z]*[^<]*' "$OUT/dom.html" | head -1 || true)
echo "report_check: ${verdict:-no self-test result (did the script run?)}"
if [[ "$verdict" != "SELFTEST PASS"* ]]; then
  tail -20 "$OUT/chrome.log"
  exit 1
fi
if grep -E "CONSOLE.*(Uncaught|Error|error)" "$OUT/chrome.log"; then
  echo "report_check: console errors above"
  exit 1
fi
if [ -n "$SHOTS" ]; then
  mkdir -p "$SHOTS"
  for width in 1280 1920; do
    timeout 120 "$CHROME" "${flags[@]}" --window-size="$width,1400" --screenshot="$SHOTS/report_$width.png" "$PAGE" 2>/dev/null
  done
  timeout 120 "$CHROME" "${flags[@]}" --window-size=1400,900 --screenshot="$SHOTS/report_compare.png" "$PAGE?compare" 2>/dev/null
  echo "report_check: screenshots in $SHOTS"
fi
