#!/usr/bin/env bash
# `cmake --install BUILD --component cli` gives a program that works where it is installed: under a
# scratch prefix, PREFIX/bin/radrecon writes an Arc/Info ASCII grid through its GDAL plugin and a
# GeoTIFF through its libtiff plugin, both found in PREFIX/lib/radrecon (io/plugin.cpp), with the
# build folder out of its sight.
# Usage: install_test.sh BUILD_DIR [CMAKE]
set -euo pipefail
build=${1:?usage: install_test.sh BUILD_DIR [CMAKE]}
cmake=${2:-cmake}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$cmake" --install "$build" --component cli --prefix "$tmp/prefix" >/dev/null
[ -x "$tmp/prefix/bin/radrecon" ] || { echo "FAIL: no PREFIX/bin/radrecon"; exit 1; }
ls "$tmp/prefix/lib/radrecon/"libradrecon_gdal.so >/dev/null || { echo "FAIL: no GDAL plugin in PREFIX/lib/radrecon"; exit 1; }
printf 'x,y,v\n0,0,1\n1,0,2\n0,1,3\n1,1,4\n' > "$tmp/s.csv"
unset RADRECON_GDAL_PLUGIN RADRECON_GEOTIFF_PLUGIN RADRECON_ASSIMP_PLUGIN RADRECON_OPENEXR_PLUGIN
for out in m.asc m.tif; do
  (cd "$tmp" && prefix/bin/radrecon interpolate --quiet --samples s.csv --method shepard --raster 4x4 \
    --domain 0,0,1,1 --out "$out") || { echo "FAIL: the installed program could not write $out"; exit 1; }
done
grep -q '^ncols *4$' "$tmp/m.asc" || { echo "FAIL: m.asc is no 4-column ASCII grid"; exit 1; }
# Little-endian TIFF magic: the file is a TIFF.
[ "$(head -c 4 "$tmp/m.tif" | od -An -tx1 | tr -d ' \n')" = "49492a00" ] || { echo "FAIL: m.tif is no TIFF"; exit 1; }
echo "cli install: PREFIX/bin/radrecon with its plugins in PREFIX/lib/radrecon"
