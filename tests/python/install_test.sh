#!/usr/bin/env bash
# `cmake --install BUILD --component python` puts the module where the interpreter looks: installed
# under a scratch prefix, its folder moved to the default prefix /usr/local must be on the
# interpreter's sys.path, and the module must import from there with its plugins beside it.
# Usage: install_test.sh BUILD_DIR PYTHON3
set -euo pipefail
build=${1:?usage: install_test.sh BUILD_DIR PYTHON3}
python=${2:?usage: install_test.sh BUILD_DIR PYTHON3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --component python --prefix "$tmp/prefix" >/dev/null
module=$(cd "$tmp/prefix" && find . -name 'radrecon.cpython-*.so' | sed 's|^\./||')
[ -n "$module" ] || { echo "FAIL: no module installed under $tmp/prefix"; exit 1; }
dir=$(dirname "$module")
"$python" -c "import sys; sys.exit(0 if '/usr/local/$dir' in sys.path else 1)" ||
  { echo "FAIL: the module goes to PREFIX/$dir, and /usr/local/$dir is not on $python's sys.path"; exit 1; }
PYTHONPATH="$tmp/prefix/$dir" "$python" -c "import radrecon; assert 'natural-neighbour' in radrecon.methods()"
echo "python install: PREFIX/$dir, on $python's path for the prefix /usr/local"
