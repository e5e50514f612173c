#!/usr/bin/env bash
# The hostile-input corpus (tests/hostile/cases.txt): every case runs radrecon on files of
# tests/hostile/inputs in a scratch folder and states its exit code and the words its message
# must contain. A refused case must leave no output (no file named out*); an accepted one is
# checked against its closed form where one is named.
# Usage: run.sh /path/to/radrecon
set -u
RADRECON=${1:?usage: run.sh /path/to/radrecon}
RADRECON=$(cd "$(dirname "$RADRECON")" && pwd)/$(basename "$RADRECON")
HERE=$(cd "$(dirname "$0")" && pwd)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_hostile.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
cp "$HERE"/inputs/* "$TMP"/
cd "$TMP" || exit 1
# Solutions in the current format, made here; and broken variants of them.
"$RADRECON" solve --scene scene_good.json --mesh grid:4 --out solution_good.json --quiet || exit 1
"$RADRECON" solve --scene paper --mesh grid:4 --out solution_paper.json --quiet || exit 1
sed '0,/"radiosity": \[/s//"radiosity": [1e999, /' solution_good.json > solution_overflow.json
sed '0,/"name": "floor"/s//"name": "ceiling"/' solution_good.json > solution_renamed.json

# check KIND FILE: the output's values (column 3 of a CSV) against a closed form.
check() {
  /usr/bin/env python3 - "$1" "$2" <<'PY'
import csv, math, sys
kind, path = sys.argv[1:]
rows = list(csv.reader(open(path)))[1:]
forms = {"plane": lambda x, y: 3 + 2 * x - 5 * y,
         "utm": lambda x, y: 0.01 * (x - 500000) - 0.02 * (y - 5400000)}
worst = 0
for r in rows:
    x, y, v = float(r[0]), float(r[1]), float(r[2])
    want = forms[kind](x, y)
    if not math.isfinite(v):
        print(f"{path}: no value at ({x}, {y})"); sys.exit(1)
    worst = max(worst, abs(v - want) / max(1.0, abs(want)))
if worst > 1e-9:
    print(f"{path}: {kind} off by {worst:.3g} (relative)"); sys.exit(1)
PY
}

cases=0 failures=0
while IFS='|' read -r name want words args check_kind; do
  case "$name" in ''|\#*) continue ;; esac
  name=$(echo "$name" | xargs); want=$(echo "$want" | xargs); words=$(echo "$words" | xargs)
  check_kind=$(echo "${check_kind:-}" | xargs)
  read -r -a argv <<< "$args"
  rm -rf out out.*
  cases=$((cases + 1))
  "$RADRECON" "${argv[@]}" > stdout.txt 2> stderr.txt
  got=$?
  problem=""
  if [ "$got" != "$want" ]; then
    problem="exit code $got, expected $want"
  elif [ -n "$words" ] && ! grep -qiF -- "$words" stderr.txt; then
    problem="message lacks '$words'"
  elif [ "$want" != 0 ] && compgen -G "out*" > /dev/null; then
    problem="output left behind: $(ls -d out*)"
  elif [ "$want" = 0 ] && [ -n "$check_kind" ]; then
    problem=$(check "$check_kind" out.csv) || true
  fi
  if [ -n "$problem" ]; then
    failures=$((failures + 1))
    echo "FAIL $name: $problem; radrecon $args"
    sed 's/^/    /' stderr.txt | head -5
  fi
done < "$HERE/cases.txt"
echo "hostile: $((cases - failures)) passed, $failures failed"
[ "$failures" = 0 ] && [ "$cases" -ge 60 ]
