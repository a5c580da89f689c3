#!/usr/bin/env bash
# Installs the Debian 12 packages penink builds, runs and tests with (idempotent: skips apt
# when every package is already installed). Used by scripts/demo.sh and scripts/test.sh;
# `deps.sh fuzz` (scripts/fuzz.sh) adds clang, which the fuzz targets alone need; `deps.sh test`
# (scripts/test.sh) adds Inkscape, which only a test needs (that Inkscape opens penink's SVG
# without warnings and keeps its metadata), and chromium with chromedriver and Selenium, which
# drive `penink preview`'s page in its test.
set -euo pipefail
pkgs=(
  cmake g++ make pkg-config            # build
  libosmesa6-dev libgl-dev libegl-dev  # headless OpenGL 4.5 core (OSMesa), EGL for GPUs
  libegl-mesa0 libgl1-mesa-dri         # Mesa's EGL (surfaceless llvmpipe): tests the --gl egl path without a GPU
  libglm-dev                           # vector maths
  libdeflate-dev                       # deflate of the terrain cache's coded blocks (core/block_codec): a
                                       # whole-buffer coder, a quarter faster than zlib to decode 256-node blocks
  libgdal-dev                          # DEM input (GeoTIFF, ASCII grid, ...)
  libgeographiclib-dev                 # geographic -> UTM
  libcgal-dev                          # mesh I/O
  libopenimageio-dev                   # raster output (PNG, TIFF, JPEG, WebP, EXR): the penink_oiio module
  libcli11-dev libtoml11-dev nlohmann-json3-dev  # CLI, scene/style files
  libcpp-httplib-dev                   # penink preview: the local web server
  libopenmpi-dev openmpi-bin           # distributed runs (mpirun -n N penink fill): the penink_mpi module
  libgtest-dev libbenchmark-dev        # tests, benchmarks
  librsvg2-bin ghostscript poppler-utils         # output checks in tests
  dpkg-dev groff-base                  # package test: cpack -G DEB runs dpkg-shlibdeps; groff checks the man page
)
if [ "${1:-}" = fuzz ]; then
  pkgs+=(clang)                        # libFuzzer and the sanitizers' runtimes (scripts/fuzz.sh)
fi
if [ "${1:-}" = test ]; then
  pkgs+=(inkscape)                     # the SVG checked in the editor it is made for
  pkgs+=(chromium chromium-driver python3-selenium)  # penink preview driven in a headless browser
fi
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "penink: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
