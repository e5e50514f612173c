#!/usr/bin/env bash
# Behaviour unchanged: `radrecon paper` gives the norms recorded in errors_baseline.json (before
# the issue-8 restructuring). Bit for bit on this toolchain, built for x86-64-v3 (CMake's
# RADRECON_ARCH); the test allows 1e-12 relative for another CPU's libm or another instruction set
# (a build for plain x86-64 differs by at most 9e-13), and the report says whether the run was
# bit-identical.
# Usage: norms_unchanged.sh /path/to/radrecon
set -euo pipefail
RADRECON=${1:?usage: norms_unchanged.sh /path/to/radrecon}
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_norms.XXXXXX")
trap 'rm -rf "$OUT"' EXIT
"$RADRECON" paper --out "$OUT" --quiet
python3 "$HERE/../../scripts/compare_norms.py" "$HERE/errors_baseline.json" "$OUT/errors.json" --rel-tol 1e-12
