#!/usr/bin/env bash
# `cmake --install BUILD --component python` puts the module where the interpreter looks: installed
# under a scratch prefix, its folder moved to the default prefix /usr/local must be on the
# interpreter's sys.path, and the module must work from there with its plugins beside it: it
# solves an OBJ model (read by the assimp plugin), and is the installed copy, not the build's.
# Usage: install_test.sh BUILD_DIR PYTHON3 [CMAKE]
set -euo pipefail
build=${1:?usage: install_test.sh BUILD_DIR PYTHON3 [CMAKE]}
python=${2:?usage: install_test.sh BUILD_DIR PYTHON3 [CMAKE]}
cmake=${3:-cmake}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$cmake" --install "$build" --component python --prefix "$tmp/prefix" >/dev/null
module=$(cd "$tmp/prefix" && find . -name 'radrecon.cpython-*.so' | sed 's|^\./||')
[ -n "$module" ] || { echo "FAIL: no module installed under $tmp/prefix"; exit 1; }
dir=$(dirname "$module")
"$python" -c "import sys; sys.exit(0 if '/usr/local/$dir' in sys.path else 1)" ||
  { echo "FAIL: the module goes to PREFIX/$dir, and /usr/local/$dir is not on $python's sys.path"; exit 1; }
# A floor under a lamp facing down (MTL Ke: an emitter), as one OBJ with its material file.
cat > "$tmp/room.mtl" <<'MTL'
newmtl floor
Kd 0.5 0.5 0.5
newmtl lamp
Kd 0 0 0
Ke 10 10 10
MTL
cat > "$tmp/room.obj" <<'OBJ'
mtllib room.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0.25 0.25 1
v 0.75 0.25 1
v 0.75 0.75 1
v 0.25 0.75 1
usemtl floor
f 1 2 3 4
usemtl lamp
f 5 8 7 6
OBJ
(cd "$tmp" && PYTHONPATH="$tmp/prefix/$dir" "$python" - "$tmp/prefix" <<'PY')
import os, sys
import radrecon
prefix = os.path.realpath(sys.argv[1])
assert os.path.realpath(radrecon.__file__).startswith(prefix), radrecon.__file__
sol = radrecon.solve("room.obj", "grid:2")
assert sol.stats["converged"] and len(sol.surfaces) == 2, sol.stats
PY
echo "python install: PREFIX/$dir, on $python's path for the prefix /usr/local, the module and its plugins working from there"
