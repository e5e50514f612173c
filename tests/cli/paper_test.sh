#!/usr/bin/env bash
# `radrecon paper` end to end, with a small reference: every output written, every table entry
# with all its figures. Labelled slow (the Release tree runs it; under the sanitizers it would
# take minutes, and its parts are unit-tested there).
# Usage: paper_test.sh /path/to/radrecon
set -u

RADRECON=${1:?usage: paper_test.sh /path/to/radrecon}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_paper_test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
RADRECON_COMMAND=()
# shellcheck source=harness.sh
source "$(dirname "$0")/harness.sh"

# --- the paper experiment, with a small reference to stay quick ---------------------------
run paper paper --out "$TMP/paper" --reference 100 --quiet
expect_rc paper 0
for f in errors.json table1.md table2.md solutions/reference.json solutions/grid16.json solutions/quadtree.json \
         figures/fig1_quadtree.png figures/fig2_reference_ground.png figures/fig3_bilinear_difference.png \
         figures/fig4_constant_difference.png figures/fig2_reference_view.png figures/fig2_reference_closeup.png \
         figures/fig3_bicubic_view.png figures/fig4_natural-neighbour_closeup.png report.html; do
  [ -s "$TMP/paper/$f" ] || fail "paper: $f was not written"
done
python3 - "$TMP/paper/errors.json" <<'EOF' || fail "paper: errors.json lacks a table entry"
import json, sys
doc = json.load(open(sys.argv[1]))
for table, method in [("grid", "constant"), ("grid", "bilinear"), ("grid", "bicubic"), ("grid", "shepard"),
                      ("grid", "multiquadric"), ("grid", "natural-neighbour"), ("quadtree", "constant"),
                      ("quadtree", "shepard"), ("quadtree", "multiquadric"), ("quadtree", "natural-neighbour"),
                      ("grid", "hermite"), ("grid", "linear"), ("grid", "clough-tocher"), ("grid", "thin-plate"),
                      ("grid", "sibson-c1"), ("grid", "laplace"), ("quadtree", "gouraud"), ("quadtree", "linear"),
                      ("grid+barriers", "thin-plate"), ("quadtree+barriers", "sibson-c1")]:
    assert set(doc[table][method]) == {"L1", "L2", "RMSE", "Linf", "SSIM", "gradient_L2", "overshoot"}, (table, method)
    assert 0 < doc[table][method]["SSIM"] <= 1, (table, method)
assert doc["settings"]["ground_leaves"] == 286
assert "barriers" in doc["settings"] and "border_samples" not in doc["settings"], "settings of rules not used"
EOF

# --- run again into the same folder without barriers: nothing of the first run's Table 3 -------
[ -s "$TMP/paper/table3.md" ] && [ -s "$TMP/paper/figures/fig5_natural-neighbour_difference.png" ] ||
  fail "paper: the run with barriers wrote no Table 3 or Fig. 5"
echo mine > "$TMP/paper/figures/fig5_my_sketch.png"  # a file of the user's, named like a figure
run again paper --out "$TMP/paper" --reference 32 --no-barriers
expect_rc again 0 && expect_stderr_has again "removed"
[ -s "$TMP/paper/figures/fig5_my_sketch.png" ] || fail "again: removed a file the earlier run did not write"
# The list is exactly the files written (all but the user's and the list itself), as find sees them.
[ "$(sort "$TMP/paper/.radrecon-paper-files")" = "$(cd "$TMP/paper" && find . -type f ! -name fig5_my_sketch.png ! -name .radrecon-paper-files | sed 's|^\./||' | sort)" ] ||
  fail "again: the list is not the files written"
[ -e "$TMP/paper/table3.md" ] && fail "again: table3.md of the earlier run is left beside the new tables"
ls "$TMP/paper/figures" | grep -v fig5_my_sketch | grep -q '^fig[5-8]_' && fail "again: Fig. 5-8 of the earlier run are left"
[ -s "$TMP/paper/table1.md" ] || fail "again: no table1.md"
python3 -c 'import json, sys; s = json.load(open(sys.argv[1]))["settings"]; assert "barriers" not in s and "border_samples" not in s' \
  "$TMP/paper/errors.json" || fail "again: errors.json describes barriers the run did not use"

finish paper_test
