#!/usr/bin/env bash
# `radrecon compare` as a user meets it: identical pictures give zeros and SSIM 1, a known
# difference gives its L1 and Linf, thresholds set the exit code, --json has the keys of
# errors.json, --diff is mid-grey where A = B, solutions compare, and bad input exits with 2 and
# a message naming the files.
# Usage: compare_test.sh /path/to/radrecon   (needs python3 for the PFM inputs and the checks)
set -u

RADRECON=${1:?usage: compare_test.sh /path/to/radrecon}
RADRECON=$(cd "$(dirname "$RADRECON")" && pwd)/$(basename "$RADRECON")  # the test runs in its own folder
HERE=$(cd "$(dirname "$0")" && pwd)
command -v python3 >/dev/null || { echo "SKIP: no python3"; exit 77; }
TMP=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_compare_test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
cd "$TMP" || exit 1
RADRECON_COMMAND=(compare)
# shellcheck source=harness.sh
source "$HERE/harness.sh"

# check_json NAME PYTHON-EXPRESSION: the expression, over j = the JSON on NAME.stdout, is true.
check_json() {
  python3 -c "import json, math, sys; j = json.load(open('$1.stdout')); sys.exit(0 if ($2) else 1)" 2>"$1.pyerr" ||
    fail "$1: not true of its JSON: $2; $(head -c 300 "$1.pyerr") stdout: $(head -c 600 "$1.stdout")"
}

# --- data: 20 x 16 RGB PFMs; a differs from b by +0.5 at one value and -0.25 at another ---------
python3 - <<'EOF'
import struct
def pfm(name, w, h, f, magic=b'PF', channels=3):
    with open(name, 'wb') as o:
        o.write(magic + b'\n%d %d\n-1.0\n' % (w, h))
        for j in range(h):
            for i in range(w):
                for c in range(channels):
                    o.write(struct.pack('<f', f(i, j, c)))
ref = lambda i, j, c: 1.0 + 0.125 * i + 0.0625 * j + c  # exact in float; largest 6.3125
def a(i, j, c):
    v = ref(i, j, c)
    if (i, j, c) == (3, 4, 1): v += 0.5
    if (i, j, c) == (15, 12, 0): v -= 0.25
    return v
pfm('b.pfm', 20, 16, ref)
pfm('a.pfm', 20, 16, a)
pfm('small.pfm', 10, 16, ref)
pfm('grey.pfm', 20, 16, lambda i, j, c: 1.0, magic=b'Pf', channels=1)
# No value (NaN, as interpolate writes outside the hull with outside=none) in the first 4 columns;
# the same with a known difference of 0.5 at (10, 8), and with values where b_hole has none.
nan = float('nan')
pfm('b_hole.pfm', 20, 16, lambda i, j, c: nan if i < 4 else ref(i, j, c), magic=b'Pf', channels=1)
pfm('a_hole.pfm', 20, 16, lambda i, j, c: nan if i < 4 else ref(i, j, c) + (0.5 if (i, j) == (10, 8) else 0), magic=b'Pf', channels=1)
pfm('full.pfm', 20, 16, ref, magic=b'Pf', channels=1)
EOF

# --- identical pictures ----------------------------------------------------------------------
run same b.pfm b.pfm
expect_rc same 0
grep -qE '^L1 +0$' same.stdout || fail "same: L1 is not 0: $(cat same.stdout)"
grep -qE '^Linf +0$' same.stdout || fail "same: Linf is not 0: $(cat same.stdout)"
grep -qE '^SSIM +1$' same.stdout || fail "same: SSIM is not 1: $(cat same.stdout)"
grep -qE '^overshoot +n/a' same.stdout || fail "same: overshoot is not n/a: $(cat same.stdout)"

# --- values missing in both: left out of the norms (a picture against itself: zeros, SSIM 1) --
run holes b_hole.pfm b_hole.pfm --threshold RMSE=1e-12
expect_rc holes 0
grep -qE '^L1 +0$' holes.stdout && grep -qE '^SSIM +1$' holes.stdout || fail "holes: not 0 and 1: $(cat holes.stdout)"
grep -qF '64 value(s) missing (NaN) in both' holes.stdout || fail "holes: the missing values not counted: $(cat holes.stdout)"
# Missing in both is no difference: mid-grey, as a picture against itself (it was drawn black).
run hole_grey b_hole.pfm b_hole.pfm --diff hole_grey.png
run same_grey b.pfm b.pfm --diff same_grey.png
expect_rc hole_grey 0 && expect_rc same_grey 0
cmp -s hole_grey.png same_grey.png || fail "hole_grey: the difference image is not mid-grey where both are missing"
run hole_diff a_hole.pfm b_hole.pfm --json
expect_rc hole_diff 0
check_json hole_diff "abs(j['Linf'] - 0.5) < 1e-15 and abs(j['L1'] - 0.5 / 256) < 1e-15 and j['count'] == 256 and j['missing_in_both'] == 64"
# Missing in one only: the figures are NaN, and a threshold says nan as the table does.
run hole_one b_hole.pfm full.pfm --threshold RMSE=1
expect_rc hole_one 1
grep -qE '^RMSE +nan$' hole_one.stdout || fail "hole_one: RMSE is not nan: $(cat hole_one.stdout)"
grep -qF 'RMSE = nan is above 1' hole_one.stderr || fail "hole_one: threshold message: $(cat hole_one.stderr)"
grep -qF '64 value(s) missing in one picture only' hole_one.stdout || fail "hole_one: not said: $(cat hole_one.stdout)"

# --- a known difference: 960 values, |e| = 0.5 and 0.25 --------------------------------------
run known a.pfm b.pfm --json
expect_rc known 0
check_json known "all(k in j for k in ('L1', 'L2', 'RMSE', 'Linf', 'SSIM', 'gradient_L2', 'overshoot'))"
check_json known "abs(j['L1'] - 0.75 / 960) < 1e-15 and abs(j['Linf'] - 0.5) < 1e-15"
check_json known "abs(j['L2'] - 0.3125 / 960) < 1e-15 and j['overshoot'] is None"
# Each lone error e gives its four neighbours a difference quotient of e / 2: 4 (e/2)^2 each.
check_json known "abs(j['gradient_L2'] - (0.25 + 0.0625) / 960) < 1e-15"
check_json known "0.99 < j['SSIM'] < 1 and j['width'] == 20 and j['height'] == 16 and j['channels'] == 3"
check_json known "j['white'] == 6.3125 and j['thresholds_exceeded'] == []"

# --- thresholds ------------------------------------------------------------------------------
run over a.pfm b.pfm --threshold Linf=0.4
expect_rc over 1
expect_stderr_has over "Linf = 0.5 is above 0.4"
grep -qE '^Linf +0.5$' over.stdout || fail "over: the figures are not printed before exit 1"
run under a.pfm b.pfm --threshold Linf=0.6 --threshold L1=0.001 --threshold SSIM=0.9
expect_rc under 0
run ssim_low a.pfm b.pfm --threshold SSIM=0.99999
expect_rc ssim_low 1
expect_stderr_has ssim_low "SSIM ="
run json_over a.pfm b.pfm --json --threshold RMSE=0.001
expect_rc json_over 1
check_json json_over "len(j['thresholds_exceeded']) == 1 and j['thresholds_exceeded'][0].startswith('RMSE')"
run bad_key a.pfm b.pfm --threshold overshoot=1
expect_rc bad_key 2
expect_stderr_has bad_key "--threshold"
run bad_value a.pfm b.pfm --threshold L1=abc
expect_rc bad_value 2

# --- the difference image --------------------------------------------------------------------
run diff a.pfm b.pfm --diff d.png
expect_rc diff 0
[ -f d.png ] || fail "diff: no d.png"
# Decode the PNG (8-bit RGB, any filter) and look at pixels: the centre (A = B) is mid-grey;
# PFM row 4 from the bottom is the picture's row 11 from the top, where A - B = +0.5 in green:
# 0.5 + 2 * 0.5 / 6.3125 = 0.6584 -> 168.
python3 - <<'EOF' || fail "diff: wrong pixels"
import struct, sys, zlib
d = open('d.png', 'rb').read()
pos, idat = 8, b''
while pos < len(d):
    n = struct.unpack('>I', d[pos:pos + 4])[0]
    t, c = d[pos + 4:pos + 8], d[pos + 8:pos + 8 + n]
    if t == b'IHDR': w, h, depth, colour = struct.unpack('>IIBB', c[:10])
    if t == b'IDAT': idat += c
    pos += 12 + n
assert (depth, colour) == (8, 2), (depth, colour)
raw, bpp, stride = zlib.decompress(idat), 3, 3 * w
rows, prev, k = [], bytearray(stride), 0
for y in range(h):
    f, line = raw[k], bytearray(raw[k + 1:k + 1 + stride]); k += 1 + stride
    for x in range(stride):
        a = line[x - bpp] if x >= bpp else 0; b = prev[x]; c = prev[x - bpp] if x >= bpp else 0
        if f == 1: line[x] = (line[x] + a) & 255
        elif f == 2: line[x] = (line[x] + b) & 255
        elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line); prev = line
px = lambda x, y: tuple(rows[y][3 * x:3 * x + 3])
ok = (w, h) == (20, 16) and px(10, 8) == (128, 128, 128) and px(3, 11) == (128, 168, 128)
if not ok: print('size', w, h, 'centre', px(10, 8), 'spike', px(3, 11), file=sys.stderr)
sys.exit(0 if ok else 1)
EOF
run diff_pfm a.pfm b.pfm --diff d.pfm
expect_rc diff_pfm 2
[ -e d.pfm ] && fail "diff_pfm: wrote d.pfm"

# --- refused input ---------------------------------------------------------------------------
run sizes a.pfm small.pfm
expect_rc sizes 2
expect_stderr_has sizes "a.pfm"
expect_stderr_has sizes "small.pfm"
run channels a.pfm grey.pfm
expect_rc channels 2
expect_stderr_has channels "grey.pfm"
run missing a.pfm nothere.pfm
expect_rc missing 2
expect_stderr_has missing "nothere.pfm"
printf 'PF\n20 16\n-1.0\nshort' >trunc.pfm
run truncated a.pfm trunc.pfm
expect_rc truncated 2
expect_stderr_has truncated "trunc.pfm"
run one_arg a.pfm
expect_rc one_arg 2

# --- rasters from `radrecon interpolate` and PNGs ----------------------------------------------
awk 'BEGIN { srand(7); print "x,y,f"; for (k = 0; k < 60; k++) { x = rand(); y = rand(); printf "%.17g,%.17g,%.17g\n", x, y, sin(3 * x) + y * y } }' >s.csv
"$RADRECON" interpolate --samples s.csv --method natural-neighbour --raster 40x30 --domain 0,0,1,1 --out nn.pfm --quiet &&
  "$RADRECON" interpolate --samples s.csv --method shepard --raster 40x30 --domain 0,0,1,1 --out sh.pfm --quiet &&
  "$RADRECON" interpolate --samples s.csv --method shepard --raster 40x30 --domain 0,0,1,1 --out sh.png --quiet &&
  "$RADRECON" interpolate --samples s.csv --method natural-neighbour --raster 40x30 --domain 0,0,1,1 --out nn.png --quiet ||
  fail "interpolate: could not make the rasters"
run rasters sh.pfm nn.pfm --json
expect_rc rasters 0
check_json rasters "j['channels'] == 1 and j['L1'] > 0 and j['SSIM'] < 1 and j['gradient_L2'] > 0"
run pngs sh.png nn.png --json
expect_rc pngs 0
check_json pngs "j['white'] == 1 and 0 < j['L1'] < 1 and j['channels'] == 3"
run png_same nn.png nn.png --json
check_json png_same "j['L1'] == 0 and j['SSIM'] == 1"
# --white with PNGs divides their values, and the summary says so (it said "as stored").
run png_white sh.png nn.png --white 0.5
expect_rc png_white 0
grep -qF "white 0.5 (PNG values divided by --white)" "$TMP/png_white.stdout" ||
  fail "png_white: the summary does not say --white divides the PNG values: $(cat "$TMP/png_white.stdout")"
run mixed sh.pfm nn.png
expect_rc mixed 2
expect_stderr_has mixed "same kind"
cp nn.png nn_before.png
run diff_over_input sh.png nn.png --diff ./nn.png
expect_rc diff_over_input 2
cmp -s nn.png nn_before.png || fail "diff_over_input: an input was overwritten"

# --- solutions -------------------------------------------------------------------------------
"$RADRECON" solve --scene paper --mesh grid:12 --out s12.json --quiet &&
  "$RADRECON" solve --scene paper --mesh grid:12 --residual 1e-2 --out s12_rough.json --quiet &&
  "$RADRECON" solve --scene paper --mesh grid:8 --out s8.json --quiet || fail "solve: could not make the solutions"
run solutions s12_rough.json s12.json --json
expect_rc solutions 0
check_json solutions "j['kind'] == 'solutions' and j['L1'] > 0 and j['gradient_L2'] > 0 and 0 < j['SSIM'] < 1 and j['overshoot'] is None"
run solutions_same s12.json s12.json
expect_rc solutions_same 0
grep -qE '^SSIM +1$' solutions_same.stdout || fail "solutions_same: SSIM is not 1: $(cat solutions_same.stdout)"
run meshes s8.json s12.json
expect_rc meshes 2
expect_stderr_has meshes "not solutions of the same mesh"
expect_stderr_has meshes "s8.json"
run solution_diff s12_rough.json s12.json --diff sd.png
expect_rc solution_diff 2
[ -e sd.png ] && fail "solution_diff: wrote sd.png"
run kinds s12.json b.pfm
expect_rc kinds 2

# Figures that cannot be written to stdout (a full device, a closed stdout) are an output that
# failed: exit 2 with the system's reason, not 0 (an empty file had passed for a comparison).
"$RADRECON" compare a.pfm b.pfm --json >/dev/full 2>stdout_full.stderr
echo $? >stdout_full.rc
expect_rc stdout_full 2
expect_stderr_has stdout_full "radrecon: error: standard output: cannot write: No space left on device"
"$RADRECON" compare a.pfm b.pfm >&- 2>stdout_closed.stderr
echo $? >stdout_closed.rc
expect_rc stdout_closed 2
expect_stderr_has stdout_closed "radrecon: error: standard output: cannot write"
# --diff naming the file stdout goes to: refused before any work (the figures and the picture
# would be written into one file).
"$RADRECON" compare a.pfm b.pfm --diff to_stdout.png >to_stdout.png 2>diff_stdout.stderr
echo $? >diff_stdout.rc
expect_rc diff_stdout 2
expect_stderr_has diff_stdout "--diff: 'to_stdout.png' is the file standard output goes to"
[ -s to_stdout.png ] && fail "diff_stdout: wrote into to_stdout.png"
# --help's text is not checked so (CLI11's own).
"$RADRECON" compare --help >/dev/full 2>help_full.stderr
echo $? >help_full.rc
expect_rc help_full 0

run help --help
expect_rc help 0
for word in --diff --threshold --json SSIM gradient_L2 overshoot "mid-grey"; do
  grep -qF -- "$word" help.stdout || fail "help: does not mention $word"
done

finish compare_test
