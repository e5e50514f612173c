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
  python-matplotlib-data  # a real elevation model (jacksboro_fault_dem.npz) for reconstruct.dem_edges
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done" >&2
