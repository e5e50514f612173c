#!/usr/bin/env bash
# Installs every Debian package that radrecon's build, tests and benchmarks need.
# Idempotent: does nothing (and needs no network) when everything is present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libgtest-dev libgmock-dev libbenchmark-dev
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev libnanoflann-dev
  nlohmann-json3-dev libcli11-dev libpng-dev libopenexr-dev time
  libassimp-dev  # mesh import: OBJ/MTL, glTF 2.0, PLY (src/io/mesh_import.h)
  python3-scipy  # the agreement tests against scipy (reconstruct.scipy_*)
  chromium       # the report checked in a real browser (tests/paper/report_check.sh)
  libgdal-dev gdal-bin python3-gdal  # interpolate to GeoTIFF and other GDAL rasters; its test reads them back
  libtiff-dev libgeotiff-dev libproj-dev  # GeoTIFF without GDAL's start-up (src/io/geotiff.h)
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module (python/) and its tests
  clang-14 libclang-rt-14-dev libomp-14-dev llvm-14  # the sanitized tree and its fuzzers (make test-asan, make fuzz); llvm-14: the symbolizer
  python-matplotlib-data  # a real elevation model (jacksboro_fault_dem.npz) for reconstruct.dem_edges
  assimp-testmodels  # the 10,000-triangle benchmark scene's model (bench/scenes/wuson_trio.json)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -ne 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  echo "setup: done" >&2
fi

# The Khronos glTF validator (npm's gltf-validator) for `radrecon export`'s test, where node is
# installed; into .tools/npm of the checkout. Without node or the registry the test runs without it.
tools="$(cd "$(dirname "$0")/.." && pwd)/.tools/npm"
if command -v npm >/dev/null && [ ! -d "$tools/node_modules/gltf-validator" ]; then
  echo "setup: npm install gltf-validator (into .tools/npm)" >&2
  npm install --no-audit --no-fund --silent --prefix "$tools" gltf-validator@2.0.0-dev.3.10 >/dev/null 2>&1 ||
    echo "setup: npm install gltf-validator failed; the export test runs without it" >&2
fi
