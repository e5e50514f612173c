#!/usr/bin/env bash
# `radrecon interpolate` at the edges of what it takes: values too small for the 32-bit floats of
# a PFM or a float32 GeoTIFF (refused, not written as zeros), clough-tocher on samples
# collinear to rounding (refused, naming the sample; linear takes them), and a gdal_grid user's
# slips (a domain apart from the samples, gdal_grid's parameter names, a missing query file).
# Usage: interpolate_edges_test.sh /path/to/radrecon
set -u

RADRECON=${1:?usage: interpolate_edges_test.sh /path/to/radrecon}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_interpolate_edges_test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
RADRECON_COMMAND=(interpolate)
# shellcheck source=harness.sh
source "$(dirname "$0")/harness.sh"

# --- values too small for 32-bit floats are refused, not written as zeros (an outside-in trial) --
printf 'x,y,z\n0,0,1e-50\n1,0,2e-50\n0,1,3e-50\n1,1,4e-50\n' > "$TMP/tiny.csv"
refuse tiny_pfm "below a 32-bit float's normal range" "$TMP/tiny.pfm" --samples "$TMP/tiny.csv" --method bilinear --raster 4x4 --domain 0,0,1,1
refuse tiny_tif "give --type float64" "$TMP/tiny.tif" --samples "$TMP/tiny.csv" --method bilinear --raster 4x4 --domain 0,0,1,1
printf 'x,y,z\n0,0,1e-33\n1,0,2e-33\n0,1,3e-33\n1,1,4e-33\n' > "$TMP/small.csv"  # normal floats: kept
run small_pfm --samples "$TMP/small.csv" --method bilinear --raster 4x4 --domain 0,0,1,1 --out "$TMP/small.pfm" --quiet
expect_rc small_pfm 0
run tiny_tif64 --samples "$TMP/tiny.csv" --method bilinear --raster 4x4 --domain 0,0,1,1 --type float64 --out "$TMP/tiny64.tif" --quiet
expect_rc tiny_tif64 0
run tiny_csv --samples "$TMP/tiny.csv" --method bilinear --queries "$TMP/tiny.csv" --out "$TMP/tiny_out.csv" --quiet
if expect_rc tiny_csv 0; then
  grep -q '^1,1,4e-50$' "$TMP/tiny_out.csv" || fail "tiny_csv: the corner's 4e-50 not kept: $(cat "$TMP/tiny_out.csv")"
fi

# --- clough-tocher on samples collinear to rounding names the sample and the cause -----------------
printf 'x,y,z\n0,0,1\n1,0.1,2\n2,0.2,3\n3,0.30000000000000004,4\n4,0.4,5\n' > "$TMP/collinear_rounding.csv"
printf 'x,y\n2.5,0.25\n' > "$TMP/collinear_q.csv"
refuse ct_collinear "lie on one line to rounding" "$TMP/ct_collinear.csv" --samples "$TMP/collinear_rounding.csv" \
  --method clough-tocher --queries "$TMP/collinear_q.csv"
run ct_collinear_linear --samples "$TMP/collinear_rounding.csv" --method linear --queries "$TMP/collinear_q.csv" \
  --out "$TMP/ct_collinear_linear.csv" --quiet
if expect_rc ct_collinear_linear 0; then
  grep -q '^2.5,0.25,3.5$' "$TMP/ct_collinear_linear.csv" || fail "ct_collinear_linear: $(cat "$TMP/ct_collinear_linear.csv")"
fi

# --- a gdal_grid user's slips (an outside-in trial) ------------------------------------------------
# A domain that misses every sample (swapped or other-unit coordinates): a warning, not silence.
printf 'x,y,v\n0,0,1\n1,0,2\n0,1,3\n' > "$TMP/three.csv"
run far_domain --samples "$TMP/three.csv" --method linear --raster 2x2 --domain 5,5,6,6 --out "$TMP/far.csv"
expect_rc far_domain 0
expect_stderr_has far_domain "the domain [5, 5, 6, 6] does not meet the samples' bounding box [0, 0, 1, 1]"
run near_domain --samples "$TMP/three.csv" --method linear --raster 2x2 --domain 0.5,0.5,6,6 --out "$TMP/near.csv"
expect_stderr_lacks near_domain "does not meet"
# gdal_grid's power: the hint names mu.
refuse shepard_power "its exponent is mu, gdal_grid's power: mu=2" "$TMP/power.csv" --samples "$TMP/three.csv" \
  --method shepard --param power=2 --raster 2x2 --domain 0,0,1,1
# Other tools' names and typos of a method: a suggestion.
refuse method_typo "unknown method 'natural-neighbor' (did you mean natural-neighbour?)" "$TMP/typo.csv" \
  --samples "$TMP/three.csv" --method natural-neighbor --raster 2x2 --domain 0,0,1,1
refuse method_idw "(did you mean shepard?)" "$TMP/idw.csv" --samples "$TMP/three.csv" --method idw --raster 2x2 --domain 0,0,1,1
refuse method_far "unknown method 'kriging'; valid methods" "$TMP/kriging.csv" --samples "$TMP/three.csv" --method kriging \
  --raster 2x2 --domain 0,0,1,1
# A query file that is not there, named as the output too: said to be missing (it was "the input
# file; refusing to overwrite it").
refuse missing_queries "cannot open CSV file" "$TMP/absent.csv" --samples "$TMP/three.csv" --method linear \
  --queries "$TMP/absent.csv"
expect_stderr_lacks missing_queries "refusing to overwrite"

finish interpolate_edges_test
