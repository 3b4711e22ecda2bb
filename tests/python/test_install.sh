#!/usr/bin/env bash
# `cmake --install` of the Python package into a scratch prefix: the installed package imports
# and renders without the build tree on PYTHONPATH (ctest python.install).
set -euo pipefail
build=$1 python=$2 source=$3
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" --component python >/dev/null
site="$prefix/lib/python3/dist-packages"
test -f "$site/snell/__init__.py"
cd "$prefix"
PYTHONPATH="$site" "$python" - "$source" "$site" <<'PY'
import sys, snell
assert snell.__file__.startswith(sys.argv[2]), snell.__file__
img = snell.load_file(sys.argv[1] + "/scenes/droplet/droplet.xml", res_x=32, res_y=24).render(spp=1)
print("installed snell renders", img.shape)
assert img.shape == (24, 32, 3)
PY
