#!/usr/bin/env bash
# `radrecon interpolate` as a user meets it: every method is exact at its samples, bilinear and
# natural-neighbour reproduce a linear function, rasters come out with the right size, and every
# refused input exits with code 2, a message, and no output file.
# Usage: interpolate_test.sh /path/to/radrecon
set -u

RADRECON=${1:?usage: interpolate_test.sh /path/to/radrecon}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_interpolate_test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
RADRECON_COMMAND=(interpolate)
# shellcheck source=harness.sh
source "$(dirname "$0")/harness.sh"



# check_values NAME OUT.csv EXPECTED.csv TOL: same rows, same x,y, values within TOL (no NaN).
check_values() {
  local msg
  msg=$(awk -F',' -v tol="$4" '
    NR == FNR { if (FNR > 1) { n++; for (c = 1; c <= NF; c++) e[n, c] = $c; ne = NF }; next }
    FNR == 1 { if ($1 != "x" || $2 != "y") { print "header " $0; bad = 1 }; next }
    {
      m++
      if (NF != ne) { print "row " m ": " NF " fields, expected " ne; bad = 1; next }
      for (c = 1; c <= NF; c++) {
        if ($c == "nan") { print "row " m " column " c ": nan"; bad = 1; continue }
        d = $c - e[m, c]; if (d < 0) d = -d
        if (d > tol) { printf "row %d column %d: %s, expected %s\n", m, c, $c, e[m, c]; bad = 1 }
      }
    }
    END { if (m != n) { print m " rows, expected " n; bad = 1 }; exit bad }' "$3" "$2" | head -5)
  if [ -n "$msg" ]; then fail "$1: $msg"; fi
}

# linear QUERIES.csv OUT.csv: the expected answer f = 2 + 3x - y at the queries.
linear() {
  awk -F',' 'NR == 1 { print "x,y,f"; next } { printf "%s,%s,%.17g\n", $1, $2, 2 + 3 * $1 - $2 }' "$1" >"$2"
}

# --- data ----------------------------------------------------------------------------------
# 40 random points in [0,1]^2 plus the corners (so interior queries are inside the hull);
# values f = 2 + 3x - y and g = 1 - x + 2y.
awk 'BEGIN {
  srand(20240611)
  print "# scattered samples of f = 2 + 3x - y, g = 1 - x + 2y"
  print "x,y,f,g"
  split("0 0 1 0 0 1 1 1", c, " ")
  for (k = 0; k < 4; k++) { x = c[2 * k + 1]; y = c[2 * k + 2]; printf "%.17g,%.17g,%.17g,%.17g\n", x, y, 2 + 3 * x - y, 1 - x + 2 * y }
  for (k = 0; k < 40; k++) { x = rand(); y = rand(); printf "%.17g, %.17g, %.17g, %.17g\n", x, y, 2 + 3 * x - y, 1 - x + 2 * y }
}' >"$TMP/scattered.csv"
awk -F',' '!/^#/ { print $1 "," $2 "," $3 }' "$TMP/scattered.csv" >"$TMP/scattered1.csv"
# The same as expected answers (no comment line, no spaces).
grep -v '^#' "$TMP/scattered.csv" | tr -d ' ' >"$TMP/scattered_expected.csv"

# A 5 x 4 regular grid over [0,2] x [-1,0.5], shuffled, same f and g.
awk 'BEGIN {
  srand(7)
  for (j = 0; j < 4; j++) for (i = 0; i < 5; i++) {
    x = i * 0.5; y = -1 + j * 0.5
    printf "%.17g %.17g,%.17g,%.17g,%.17g\n", rand(), x, y, 2 + 3 * x - y, 1 - x + 2 * y
  }
}' | sort -n | awk 'BEGIN { print "x,y,f,g" } { sub(/^[^ ]* /, ""); print }' >"$TMP/grid.csv"
tail -n +2 "$TMP/grid.csv" | sort -t, -k2,2g -k1,1g | awk 'BEGIN { print "x,y,f,g" } { print }' >"$TMP/grid_expected.csv"
grep -v '^x' "$TMP/grid.csv" | sort | cmp -s - <(grep -v '^x' "$TMP/grid_expected.csv" | sort) ||
  fail "test setup: grid files differ"

# Random interior queries of the unit square and of the grid.
awk 'BEGIN { srand(99); print "x,y,label"; for (k = 0; k < 30; k++) printf "%.17g,%.17g,q%d\n", 0.02 + 0.96 * rand(), 0.02 + 0.96 * rand(), k }' >"$TMP/queries.csv"
awk 'BEGIN { srand(5); print "x,y"; for (k = 0; k < 30; k++) printf "%.17g,%.17g\n", 2 * rand(), -1 + 1.5 * rand() }' >"$TMP/grid_queries.csv"

# --- exactness at the samples ----------------------------------------------------------------
for m in constant shepard multiquadric natural-neighbour; do
  run "exact_$m" --samples "$TMP/scattered.csv" --method "$m" --queries "$TMP/scattered.csv" --out "$TMP/exact_$m.csv" --quiet
  if expect_rc "exact_$m" 0; then check_values "exact_$m" "$TMP/exact_$m.csv" "$TMP/scattered_expected.csv" 1e-9; fi
done
run exact_shepard_k --samples "$TMP/scattered.csv" --method shepard --param mu=2 --param k=8 \
  --queries "$TMP/scattered.csv" --out "$TMP/exact_shepard_k.csv" --quiet
if expect_rc exact_shepard_k 0; then check_values exact_shepard_k "$TMP/exact_shepard_k.csv" "$TMP/scattered_expected.csv" 1e-9; fi
for m in bilinear bicubic; do
  run "exact_$m" --samples "$TMP/grid.csv" --method "$m" --queries "$TMP/grid_expected.csv" --out "$TMP/exact_$m.csv" --quiet
  if expect_rc "exact_$m" 0; then check_values "exact_$m" "$TMP/exact_$m.csv" "$TMP/grid_expected.csv" 1e-9; fi
done

# --- linear precision at interior points -------------------------------------------------------
linear "$TMP/queries.csv" "$TMP/queries_expected.csv"
run linear_nn --samples "$TMP/scattered1.csv" --method natural-neighbour --queries "$TMP/queries.csv" --out "$TMP/linear_nn.csv" --quiet
if expect_rc linear_nn 0; then check_values linear_nn "$TMP/linear_nn.csv" "$TMP/queries_expected.csv" 1e-9; fi
awk -F',' '{ print $1 "," $2 "," $3 }' "$TMP/grid.csv" >"$TMP/grid1.csv"
linear "$TMP/grid_queries.csv" "$TMP/grid_queries_expected.csv"
run linear_bilinear --samples "$TMP/grid1.csv" --method bilinear --queries "$TMP/grid_queries.csv" --out "$TMP/linear_bilinear.csv" --quiet
if expect_rc linear_bilinear 0; then check_values linear_bilinear "$TMP/linear_bilinear.csv" "$TMP/grid_queries_expected.csv" 1e-9; fi
# A natural cubic spline reproduces a linear function too.
run linear_bicubic --samples "$TMP/grid1.csv" --method bicubic --queries "$TMP/grid_queries.csv" --out "$TMP/linear_bicubic.csv" --quiet
if expect_rc linear_bicubic 0; then check_values linear_bicubic "$TMP/linear_bicubic.csv" "$TMP/grid_queries_expected.csv" 1e-9; fi

# The progress lines, unless --quiet.
run talk --samples "$TMP/scattered1.csv" --method constant --queries "$TMP/queries.csv" --out "$TMP/talk.csv"
expect_rc talk 0 && expect_stderr_has talk "talk.csv"
if [ -s "$TMP/exact_constant.stderr" ]; then fail "exact_constant: --quiet run printed: $(head -c 300 "$TMP/exact_constant.stderr")"; fi

# --- rasters ---------------------------------------------------------------------------------
run pfm --samples "$TMP/scattered1.csv" --method natural-neighbour --raster 7x5 --domain 0,0,1,1 --out "$TMP/r.pfm" --quiet
if expect_rc pfm 0; then
  header=$(head -c 12 "$TMP/r.pfm" | tr '\n' ' ')
  [ "$header" = "Pf 7 5 -1.0 " ] || fail "pfm: header '$header', expected 'Pf 7 5 -1.0 '"
  size=$(stat -c %s "$TMP/r.pfm")
  [ "$size" = $((12 + 7 * 5 * 4)) ] || fail "pfm: $size bytes, expected $((12 + 7 * 5 * 4))"
fi
awk -F',' '!/^#/ { print $1 "," $2 "," $3 "," $4 "," $3 }' "$TMP/scattered.csv" >"$TMP/scattered3.csv"
run pfm3 --samples "$TMP/scattered3.csv" --method shepard --raster 4x3 --domain=-1,-1,2,2 --out "$TMP/r3.PFM" --quiet
if expect_rc pfm3 0; then
  header=$(head -c 12 "$TMP/r3.PFM" | tr '\n' ' ')
  [ "$header" = "PF 4 3 -1.0 " ] || fail "pfm3: header '$header', expected 'PF 4 3 -1.0 '"
  size=$(stat -c %s "$TMP/r3.PFM")
  [ "$size" = $((12 + 4 * 3 * 12)) ] || fail "pfm3: $size bytes, expected $((12 + 4 * 3 * 12))"
fi
# A colour PFM of several batches (200 x 100 = 20,000 points; a batch is 16,384) against the
# closed form: linear interpolation reproduces the three linear functions exactly (to float).
printf 'x,y,r,g,b\n0,0,1,-2,0.5\n4,0,9,-2,4.5\n0,2,-1,4,1.5\n4,2,7,4,5.5\n1,0.5,2.5,-0.5,1.75\n' >"$TMP/linear3.csv"
run pfm_batches --samples "$TMP/linear3.csv" --method linear --raster 200x100 --domain 0,0,4,2 --out "$TMP/batches.pfm" --quiet
if expect_rc pfm_batches 0; then
  python3 - "$TMP/batches.pfm" <<'PY' || fail "pfm_batches: the values are not the three linear functions at the cell centres"
import struct, sys
data = open(sys.argv[1], "rb").read()
header = b"PF\n200 100\n-1.0\n"
assert data.startswith(header), data[:20]
values = struct.unpack("<60000f", data[len(header):])
for j in range(100):
    for i in range(200):
        x, y = (i + 0.5) * 4 / 200, (j + 0.5) * 2 / 100
        want = (1 + 2 * x - y, -2 + 3 * y, 0.5 + x + 0.5 * y)
        got = values[(j * 200 + i) * 3:(j * 200 + i) * 3 + 3]
        for g, w in zip(got, want):
            assert abs(g - w) <= 1e-6 * (1 + abs(w)), (i, j, got, want)
PY
fi
for spec in "png1 scattered1.csv 37x23" "png3 scattered3.csv 16x9"; do
  read -r name file size <<<"$spec"
  run "$name" --samples "$TMP/$file" --method multiquadric --raster "$size" --domain 0,0,1,1 --out "$TMP/$name.png" --quiet
  if expect_rc "$name" 0; then
    got=$(python3 -c 'import sys, struct
b = open(sys.argv[1], "rb").read()
assert b[:8] == b"\x89PNG\r\n\x1a\n" and b[12:16] == b"IHDR", "not a PNG"
print("%dx%d" % struct.unpack(">II", b[16:24]))' "$TMP/$name.png" 2>&1)
    [ "$got" = "$size" ] || fail "$name: PNG size '$got', expected $size"
  fi
done

# --- duplicates: merged with one warning -------------------------------------------------------
printf 'x,y,B\n0,0,1\n1,0,2\n0,1,3\n0,0,5\n1,1,4\n' >"$TMP/dup.csv"
printf 'x,y\n0,0\n' >"$TMP/origin.csv"
run dup --samples "$TMP/dup.csv" --method constant --queries "$TMP/origin.csv" --out "$TMP/dup_out.csv" --quiet
if expect_rc dup 0; then
  expect_stderr_has dup "warning"
  [ "$(grep -c . "$TMP/dup.stderr")" = 1 ] || fail "dup: expected one warning line, got: $(cat "$TMP/dup.stderr")"
  printf 'x,y,B\n0,0,3\n' >"$TMP/dup_expected.csv"
  check_values dup "$TMP/dup_out.csv" "$TMP/dup_expected.csv" 0
fi
# Two to be merged on either side of a barrier: refused naming both (merged, their mean was seen
# from both sides), nothing written.
printf 'x,y,B\n0,0,0\n1,0,100\n0,1,0\n1,1,100\n0.4999999999,0.3,0\n0.5000000001,0.3,100\n' >"$TMP/dup_wall.csv"
printf '{"type": "LineString", "coordinates": [[0.5, -1], [0.5, 2]]}\n' >"$TMP/dup_wall.geojson"
run dup_wall --samples "$TMP/dup_wall.csv" --method shepard --barriers "$TMP/dup_wall.geojson" --queries "$TMP/origin.csv" \
  --out "$TMP/dup_wall_out.csv" --quiet
expect_rc dup_wall 2
expect_stderr_has dup_wall "dup_wall.csv: samples 5 and 6 (in the order read), at (0.4999999999, 0.3) and (0.5000000001, 0.3)"
[ -e "$TMP/dup_wall_out.csv" ] && fail "dup_wall: wrote an output"

# --- refusals: exit 2, a message, no output ---------------------------------------------------
: >"$TMP/empty.csv"
printf 'x,y,B\n# no rows\n' >"$TMP/header_only.csv"
printf 'x,y,B\n0,0,1\n1,0,nan\n0,1,2\n' >"$TMP/nan.csv"
printf 'x,y,B\n0,0,1\n1,0\n0,1,2\n' >"$TMP/short.csv"
printf 'x,y,B\n0,0,1\n1,0,2\n0,one,2\n' >"$TMP/text.csv"
printf 'x,y,B\n0,0,1\n1,1,2\n2,2,3\n3,3,5\n' >"$TMP/collinear.csv"
printf 'x,y\n0,nan\n' >"$TMP/queries_nan.csv"
printf 'x,y,B\n0,0,1\n1e200,0,2\n0,1,3\n' >"$TMP/huge.csv"
printf 'x,y,B\n0,0,1e308\n1,0,-1e308\n0,1,1e308\n1,1,-1e308\n' >"$TMP/huge_values.csv"
printf 'x,y,B\n0,0,1e50\n1,0,-1e50\n0,1,1e50\n1,1,-1e50\n' >"$TMP/float_range.csv"  # within 1e100, beyond a float

S=$TMP/scattered1.csv
Q=$TMP/queries.csv
refuse missing_samples "absent.csv" "$TMP/o1.csv" --samples "$TMP/absent.csv" --method constant --queries "$Q"
refuse empty_samples "empty.csv:1" "$TMP/o2.csv" --samples "$TMP/empty.csv" --method constant --queries "$Q"
refuse no_rows "no data rows" "$TMP/o3.csv" --samples "$TMP/header_only.csv" --method constant --queries "$Q"
refuse nan_value "nan.csv:3" "$TMP/o4.csv" --samples "$TMP/nan.csv" --method shepard --queries "$Q"
refuse short_row "short.csv:3" "$TMP/o5.csv" --samples "$TMP/short.csv" --method shepard --queries "$Q"
refuse non_numeric "text.csv:4" "$TMP/o6.csv" --samples "$TMP/text.csv" --method shepard --queries "$Q"
expect_stderr_has non_numeric "column 2"
refuse unknown_method "natural-neighbour" "$TMP/o7.csv" --samples "$S" --method kriging --queries "$Q"
expect_stderr_has unknown_method "--method"
refuse unknown_param "--param" "$TMP/o8.csv" --samples "$S" --method shepard --param nu=2 --queries "$Q"
refuse negative_mu "mu" "$TMP/o9.csv" --samples "$S" --method shepard --param mu=-1 --queries "$Q"
refuse bilinear_scattered "regular grid" "$TMP/o10.csv" --samples "$S" --method bilinear --queries "$Q"
refuse bicubic_scattered "distinct x" "$TMP/o11.png" --samples "$S" --method bicubic --raster 4x4 --domain 0,0,1,1
refuse nn_collinear "collinear.csv" "$TMP/o12.csv" --samples "$TMP/collinear.csv" --method natural-neighbour --queries "$Q"
refuse raster_zero "--raster" "$TMP/o13.pfm" --samples "$S" --method constant --raster 0x5 --domain 0,0,1,1
refuse raster_no_domain "--domain" "$TMP/o14.pfm" --samples "$S" --method constant --raster 5x5
refuse bad_domain "--domain" "$TMP/o15.pfm" --samples "$S" --method constant --raster 5x5 --domain 1,0,0,1
refuse both_queries_raster "--queries" "$TMP/o16.csv" --samples "$S" --method constant --queries "$Q" --raster 5x5 --domain 0,0,1,1
refuse neither "--queries" "$TMP/o17.csv" --samples "$S" --method constant
refuse pfm_queries "raster" "$TMP/o18.pfm" --samples "$S" --method constant --queries "$Q"
refuse png_queries "raster" "$TMP/o19.png" --samples "$S" --method constant --queries "$Q"
refuse unknown_extension ".nosuchext" "$TMP/o20.nosuchext" --samples "$S" --method constant --raster 5x5 --domain 0,0,1,1
refuse pfm_two_columns "1 or 3" "$TMP/o21.pfm" --samples "$TMP/scattered.csv" --method constant --raster 5x5 --domain 0,0,1,1
refuse huge_coordinate "huge.csv:3" "$TMP/o23.csv" --samples "$TMP/huge.csv" --method shepard --queries "$Q"
refuse huge_domain "--domain" "$TMP/o24.pfm" --samples "$S" --method constant --raster 5x5 --domain=-1e200,0,1,1
refuse huge_values "huge_values.csv:2: column 3 (B): '1e308' is beyond the largest value" "$TMP/o25.csv" --samples "$TMP/huge_values.csv" --method multiquadric --queries "$Q"
refuse pfm_float_range "32-bit floats" "$TMP/o26.pfm" --samples "$TMP/float_range.csv" --method bilinear --raster 4x4 --domain 0,0,1,1
refuse bad_queries "queries_nan.csv:2" "$TMP/o22.csv" --samples "$S" --method constant --queries "$TMP/queries_nan.csv"
# No input is ever overwritten: the samples or queries named as the output, directly, through a
# symbolic link, through "..", or as a hard link, are refused before any work; so are outputs
# that cannot be written.
cp "$S" "$TMP/own.csv"
cp "$Q" "$TMP/ownq.csv"
mkdir -p "$TMP/sub"
ln -s "$TMP/own.csv" "$TMP/link.csv"
ln "$TMP/own.csv" "$TMP/hard.csv"
for out in "$TMP/own.csv" "$TMP/sub/../own.csv" "$TMP/link.csv" "$TMP/hard.csv" "$TMP/ownq.csv" \
           "$TMP/missing/../link.csv"; do
  run overwrite --samples "$TMP/own.csv" --method constant --queries "$TMP/ownq.csv" --out "$out" --quiet
  expect_rc overwrite 2
  expect_stderr_has overwrite "refusing to overwrite"
done
cmp -s "$S" "$TMP/own.csv" || fail "overwrite: the samples file was changed"
cmp -s "$Q" "$TMP/ownq.csv" || fail "overwrite: the queries file was changed"
[ -L "$TMP/link.csv" ] || fail "overwrite: the link to the samples was replaced"
[ ! -e "$TMP/missing" ] || fail "overwrite: a refused run created a folder"
refuse out_under_file "not a folder" "$TMP/own.csv/o.csv" --samples "$S" --method constant --queries "$Q"
mkdir -p "$TMP/folder.csv"
run out_is_folder --samples "$S" --method constant --queries "$Q" --out "$TMP/folder.csv" --quiet
expect_rc out_is_folder 2
expect_stderr_has out_is_folder "is a folder"
# A folder without an extension ('.') is refused as a folder, not for its extension.
(cd "$TMP" && "$RADRECON" interpolate --samples "$S" --method constant --raster 4x4 --domain 0,0,1,1 --out . \
  >"$TMP/dot.out" 2>"$TMP/dot.err"; echo $? >"$TMP/dot.rc")
[ "$(cat "$TMP/dot.rc")" = 2 ] || fail "out_is_dot: exit $(cat "$TMP/dot.rc"), expected 2"
grep -q "'.' is a folder" "$TMP/dot.err" || fail "out_is_dot: stderr: $(cat "$TMP/dot.err")"

# Out of memory: exit code 3, a message, nothing written. Not under AddressSanitizer (linked as
# libasan by gcc, into the binary by clang), whose shadow memory cannot be mapped under ulimit -v.
if ! { ldd "$RADRECON" 2>/dev/null | grep -q libasan || nm -D "$RADRECON" 2>/dev/null | grep -q __asan_init; }; then
  # A PNG takes every value at once: 16,000,000 doubles (128 MB) do not fit in 100 MB.
  # Two threads, whatever the machine: each thread's stack counts against the limit.
  (ulimit -v 100000; OMP_NUM_THREADS=2 "$RADRECON" interpolate --samples "$TMP/scattered1.csv" --method shepard --raster 4000x4000 \
     --domain 0,0,1,1 --out "$TMP/oom.png" >"$TMP/oom.stdout" 2>"$TMP/oom.stderr"; echo $? >"$TMP/oom.rc")
  expect_rc oom 3
  expect_stderr_has oom "out of memory"
  expect_no_output oom "$TMP/oom.png"
  # A PFM is written batch by batch as it is made: the same raster fits, whole.
  (ulimit -v 100000; OMP_NUM_THREADS=2 "$RADRECON" interpolate --samples "$TMP/scattered1.csv" --method shepard --raster 4000x4000 \
     --domain 0,0,1,1 --out "$TMP/streamed.pfm" --quiet >"$TMP/streamed.stdout" 2>"$TMP/streamed.stderr"; echo $? >"$TMP/streamed.rc")
  expect_rc streamed 0
  [ "$(stat -c %s "$TMP/streamed.pfm" 2>/dev/null)" = $((18 + 4000 * 4000 * 4)) ] ||
    fail "streamed: the PFM is not 18 + 4000 x 4000 x 4 bytes"
  rm -f "$TMP/streamed.pfm"
fi

# Interrupted (SIGINT) or hung up (SIGHUP) while streaming a large PFM (64,000,000 points, seconds
# of work): exit 128 + the signal's number, said, and neither the output nor its temporary file is
# left. (SIGTERM's case is tests/io/gdal_raster_check.py's, during a GDAL write.)
# Started with job control on: a script's background job otherwise has SIGINT ignored, which
# radrecon keeps (below).
for case in "INT 130 interrupted (SIGINT)" "HUP 129 hung up (SIGHUP)"; do
  read -r sig code said <<<"$case"
  set -m
  "$RADRECON" interpolate --samples "$TMP/scattered1.csv" --method shepard --raster 8000x8000 --domain 0,0,1,1 \
    --out "$TMP/interrupted.pfm" --quiet >/dev/null 2>"$TMP/interrupted.stderr" &
  pid=$!
  set +m
  for _ in $(seq 50); do ls "$TMP"/interrupted.pfm.tmp* >/dev/null 2>&1 && break; sleep 0.1; done
  kill -"$sig" "$pid"
  wait "$pid"
  rc=$?
  [ "$rc" = "$code" ] || fail "SIG$sig: exit code $rc, expected $code"
  # On the first line: no empty line before it when stderr is no terminal (a log file here).
  [ "$(head -n 1 "$TMP/interrupted.stderr")" = "radrecon: $said; no output was left half-written under its name" ] ||
    fail "SIG$sig: not said on the first line: $(cat "$TMP/interrupted.stderr")"
  if ls "$TMP"/interrupted.pfm* >/dev/null 2>&1; then fail "SIG$sig: left $(ls "$TMP"/interrupted.pfm*)"; fi
done

# A signal ignored when radrecon starts stays ignored (nohup, `trap ''`, a script's background
# job's SIGINT): the run completes, exit 0, its output whole. Its handler ended it (exit 129, 130).
for sig in HUP INT; do
  (
    trap '' "$sig"
    "$RADRECON" interpolate --samples "$TMP/scattered1.csv" --method shepard --raster 2000x2000 --domain 0,0,1,1 \
      --out "$TMP/ignored_$sig.pfm" --quiet >/dev/null 2>"$TMP/ignored_$sig.stderr" &
    pid=$!
    for _ in $(seq 100); do ls "$TMP"/ignored_"$sig".pfm.tmp* >/dev/null 2>&1 && break; sleep 0.05; done
    kill -"$sig" "$pid"
    wait "$pid"
    echo $? >"$TMP/ignored_$sig.rc"
  )
  expect_rc "ignored_$sig" 0
  [ "$(stat -c %s "$TMP/ignored_$sig.pfm" 2>/dev/null)" = $((18 + 2000 * 2000 * 4)) ] ||
    fail "ignored_$sig: the PFM is not whole: $(cat "$TMP/ignored_$sig.stderr")"
  rm -f "$TMP/ignored_$sig.pfm"
done

# An output that existed before a refused run is left as it was.
echo "keep me" >"$TMP/keep.csv"
run keep --samples "$TMP/nan.csv" --method constant --queries "$Q" --out "$TMP/keep.csv" --quiet
expect_rc keep 2
[ "$(cat "$TMP/keep.csv")" = "keep me" ] || fail "keep: a refused run changed an existing output"

# --- barriers (--barriers FILE.geojson) --------------------------------------------------------
# A wall across the unit square at x = 0.5; the right side's values moved by +100 or +200: no
# query left of the wall may change, for any method, on the CSV and the raster path alike.
printf '{"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": [[0.5, -1], [0.5, 2, 7]]}}\n' >"$TMP/wall.geojson"
for shift in 100 200; do
  awk -F',' -v s="$shift" 'NR == 1 { print; next } /^#/ { next } { v = $3; if ($1 > 0.5) v += s; print $1 "," $2 "," v }' \
    "$TMP/scattered1.csv" >"$TMP/walled_$shift.csv"
  # Left of the wall, its corners too: the left queries are inside the hull of what they see.
  printf '0.49,0,3.47\n0.49,1,2.47\n' >>"$TMP/walled_$shift.csv"
done
awk 'BEGIN { srand(3); print "x,y"; for (k = 0; k < 40; k++) printf "%.17g,%.17g\n", 0.45 * rand(), rand() }' >"$TMP/left_queries.csv"
for m in constant shepard multiquadric natural-neighbour; do
  for shift in 100 200; do
    run "wall_${m}_$shift" --samples "$TMP/walled_$shift.csv" --method "$m" --barriers "$TMP/wall.geojson" \
      --queries "$TMP/left_queries.csv" --out "$TMP/wall_${m}_$shift.csv" --quiet
    expect_rc "wall_${m}_$shift" 0
  done
  cmp -s "$TMP/wall_${m}_100.csv" "$TMP/wall_${m}_200.csv" || fail "wall_$m: a sample across the wall changed a value"
done
# Natural neighbours with the wall: the left side's plane f = 2 + 3x - y exactly.
linear "$TMP/left_queries.csv" "$TMP/left_expected.csv"
check_values wall_nn "$TMP/wall_natural-neighbour_100.csv" "$TMP/left_expected.csv" 1e-9
run wall_raster --samples "$TMP/walled_100.csv" --method natural-neighbour --barriers "$TMP/wall.geojson" \
  --raster 20x20 --domain 0,0,1,1 --out "$TMP/wall_raster.pfm"
expect_rc wall_raster 0 && expect_stderr_has wall_raster "1 barrier segments from"
printf '{"type": "LineString", "coordinates": [[0.5, 0]]}' >"$TMP/one_point.geojson"
printf '{"type": "FeatureCollection", "features": [{"type": "Feature", "geometry": {"type": "Point", "coordinates": [0, 0]}}]}' >"$TMP/point.geojson"
printf '{"type": "LineString", "coordinates": [[0, 0], [1, 1e999]]}' >"$TMP/overflow.geojson"
printf '{"type": "LineString", "coordinates": [[0, 0], [0, 0]]}' >"$TMP/zero_length.geojson"
printf '{"type": "LineString", "coordinates": [[0, 0], [1, ' >"$TMP/truncated.geojson"
refuse barrier_one_point "one_point.geojson" "$TMP/b1.csv" --samples "$S" --method shepard --queries "$Q" --barriers "$TMP/one_point.geojson"
expect_stderr_has barrier_one_point "coordinates"
refuse barrier_point "features[0].geometry" "$TMP/b2.csv" --samples "$S" --method shepard --queries "$Q" --barriers "$TMP/point.geojson"
refuse barrier_overflow "overflow.geojson:1" "$TMP/b3.csv" --samples "$S" --method shepard --queries "$Q" --barriers "$TMP/overflow.geojson"
refuse barrier_zero_length "zero_length.geojson" "$TMP/b4.csv" --samples "$S" --method natural-neighbour --queries "$Q" --barriers "$TMP/zero_length.geojson"
refuse barrier_truncated "truncated.geojson" "$TMP/b5.pfm" --samples "$S" --method constant --raster 5x5 --domain 0,0,1,1 --barriers "$TMP/truncated.geojson"
refuse barrier_missing "absent.geojson" "$TMP/b6.csv" --samples "$S" --method constant --queries "$Q" --barriers "$TMP/absent.geojson"
cp "$TMP/wall.geojson" "$TMP/wall_geojson.csv"  # a barrier file named as the output
refuse barrier_collinear "one line" "$TMP/b9.csv" --samples "$TMP/collinear.csv" --method natural-neighbour --queries "$Q" --barriers "$TMP/wall.geojson"
run barrier_overwrite --samples "$S" --method constant --queries "$Q" --barriers "$TMP/wall_geojson.csv" \
  --out "$TMP/wall_geojson.csv" --quiet
expect_rc barrier_overwrite 2 && expect_stderr_has barrier_overwrite "refusing to overwrite"

# --- border samples: samples inside [0.1, 0.9]^2 of f = 2 + 3x - y; with --border-samples on the
# unit square, natural-neighbour reproduces f out to the square's border (the border samples'
# planes are exact for a linear f); without, points beyond the samples' hull have no value.
awk 'BEGIN { srand(12); print "x,y,f"; for (k = 0; k < 60; k++) { x = 0.1 + 0.8 * rand(); y = 0.1 + 0.8 * rand(); printf "%.17g,%.17g,%.17g\n", x, y, 2 + 3 * x - y } }' >"$TMP/inner.csv"
awk 'BEGIN { srand(13); print "x,y"; for (k = 0; k < 40; k++) printf "%.17g,%.17g\n", 0.01 + 0.98 * rand(), (k % 2) * 0.98 + 0.01 }' >"$TMP/edge_queries.csv"
linear "$TMP/edge_queries.csv" "$TMP/edge_expected.csv"
run border_nn --samples "$TMP/inner.csv" --method natural-neighbour --param outside=none --border-samples \
  --domain 0,0,1,1 --queries "$TMP/edge_queries.csv" --out "$TMP/border_nn.csv"
expect_rc border_nn 0 && check_values border_nn "$TMP/border_nn.csv" "$TMP/edge_expected.csv" 1e-9
expect_stderr_has border_nn "border samples added"
run no_border_nn --samples "$TMP/inner.csv" --method natural-neighbour --param outside=none \
  --queries "$TMP/edge_queries.csv" --out "$TMP/no_border_nn.csv" --quiet
grep -q nan "$TMP/no_border_nn.csv" || fail "no_border_nn: every point had a value without border samples"
refuse border_constant "--border-samples" "$TMP/b7.csv" --samples "$S" --method constant --border-samples --queries "$Q"
refuse domain_without_border "--domain" "$TMP/b8.csv" --samples "$S" --method shepard --domain 0,0,1,1 --queries "$Q"

# --- an empty column name given is refused, not read as the default (every column) ------------
run empty_value --samples "$TMP/scattered.csv" --value "" --method shepard --queries "$TMP/queries.csv" --out "$TMP/empty_value.csv"
expect_rc empty_value 2 && expect_stderr_has empty_value "radrecon: error: --value: must not be empty"
[ -e "$TMP/empty_value.csv" ] && fail "empty_value: wrote an output"

# --- an empty value of any option is refused (--barriers "$UNSET" ran without barriers), and a
# number option's text that is no number is refused in radrecon's words, naming the option --------
run empty_barriers --samples "$TMP/scattered.csv" --barriers "" --method linear --queries "$TMP/queries.csv" --out "$TMP/empty_barriers.csv"
expect_rc empty_barriers 2 && expect_stderr_has empty_barriers "radrecon: error: --barriers: must not be empty"
[ -e "$TMP/empty_barriers.csv" ] && fail "empty_barriers: wrote an output"
run nodata_text --samples "$TMP/scattered.csv" --nodata abc --method linear --queries "$TMP/queries.csv" --out "$TMP/nodata_text.csv"
expect_rc nodata_text 2 && expect_stderr_has nodata_text "radrecon: error: --nodata: must be a number, got 'abc'"
# Nor a hexadecimal one (--nodata 0x10 was 16); nan stays the no-data value it was.
run nodata_hex --samples "$TMP/scattered.csv" --nodata 0x10 --method linear --raster 4x3 --domain 0,0,1,1 --out "$TMP/nodata_hex.tif"
expect_rc nodata_hex 2 && expect_stderr_has nodata_hex "radrecon: error: --nodata: must be a decimal number, got '0x10'"
expect_no_output nodata_hex "$TMP/nodata_hex.tif"
run nodata_nan --samples "$TMP/scattered.csv" --nodata nan --method linear --raster 4x3 --domain 0,0,1,1 --out "$TMP/nodata_nan.tif" --quiet
expect_rc nodata_nan 0

# --- refusals that say what to do: the header's separator decides the rows'; a table under an
# extension read through OGR; the methods and extensions listed are those this command takes ----
printf 'x y v\n0,0,1\n1,0,2\n0,1,3\n' > "$TMP/spaced_header.csv"
refuse spaced_header "the row has 1 field, the header has 3; the header's separator (spaces)" "$TMP/sh.csv" \
  --samples "$TMP/spaced_header.csv" --method linear --queries "$Q"
cp "$TMP/scattered1.csv" "$TMP/table.asc"
refuse table_asc "rename it if it is one" "$TMP/ta.csv" --samples "$TMP/table.asc" --method linear --queries "$Q"
refuse no_gouraud "valid methods: constant" "$TMP/ng.csv" --samples "$S" --method nosuch --queries "$Q"
if grep -q "gouraud" "$TMP/no_gouraud.stderr"; then fail "no_gouraud: interpolate listed gouraud, which it refuses"; fi

printf 'x,y,"z\n0,0,1\n1,0,2\n0,1,3\n' > "$TMP/half_quoted.csv"
refuse half_quoted "column 3 of the header, '\"z', has a double quote in its name" "$TMP/hq.csv" \
  --samples "$TMP/half_quoted.csv" --method linear --queries "$Q"
# A query table's further columns are ignored, whatever their names.
printf 'x,y,label 5"\n0.5,0.5,a\n' > "$TMP/quoted_label.csv"
run quoted_label --samples "$S" --method linear --queries "$TMP/quoted_label.csv" --out "$TMP/ql.csv" --quiet
expect_rc quoted_label 0

# --- a column named x beside --x lon is not a value column by default: its values would be written
# under the output's own x (a header x,y,x,v, which radrecon refuses to read back) ------------------
printf 'lon,lat,x,v\n0,0,7,1\n1,0,7,2\n0,1,7,3\n' > "$TMP/lonlat.csv"
run lonlat --samples "$TMP/lonlat.csv" --x lon --y lat --method linear --raster 2x2 --domain 0,0,1,1 --out "$TMP/lonlat_out.csv"
expect_rc lonlat 0 && expect_stderr_has lonlat "the column x is not interpolated"
[ "$(head -1 "$TMP/lonlat_out.csv")" = "x,y,v" ] || fail "lonlat: header $(head -1 "$TMP/lonlat_out.csv")"

# --- the raster-points limit counts a point once for each value column (the memory goes with the
# values: 10 samples of 20,000 columns took 3.4 GB on a 100 x 100 raster within the limit) -----
printf 'x,y,a,b,c\n0,0,1,2,3\n1,0,1,2,3\n0,1,1,2,3\n' > "$TMP/three_columns.csv"
refuse columns_count "400 points of 3 value columns make 1200 points, beyond the limit of 1000" "$TMP/cc.csv" \
  --samples "$TMP/three_columns.csv" --method constant --raster 20x20 --domain 0,0,1,1 --max-raster-points 1000
run columns_fit --samples "$TMP/three_columns.csv" --method constant --raster 20x20 --domain 0,0,1,1 \
  --max-raster-points 1200 --out "$TMP/cf.csv" --quiet
expect_rc columns_fit 0

# --- a raster of no values at all is written, with a warning ----------------------------------
run no_value --samples "$TMP/scattered1.csv" --method linear --param outside=none --raster 3x2 --domain 50,50,60,60 \
  --out "$TMP/no_value.pfm" --quiet
expect_rc no_value 0 && expect_stderr_has no_value "no point has a value"

finish interpolate_test
