#!/usr/bin/env bash
# Build step for scenes/bunny_sphere (run by cmake/module_scenes.cmake, or by hand): installs the
# pinned npm package `bunny` under NPM_PREFIX and converts it to OBJ_OUT. Never fails the build:
# without node/npm or the registry it says so and leaves OBJ_OUT absent, and the bunny scene is
# skipped in favour of scenes/glass_sphere (the same set-up with a cube).
# Usage: scripts/make_bunny_mesh.sh NPM_PREFIX OBJ_OUT [VERSION]
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
prefix=$1
out=$2
version=${3:-1.0.1}

fallback() {
  echo "make_bunny_mesh: $1; scenes/bunny_sphere is unavailable, use scenes/glass_sphere/glass_sphere.xml (a cube inside the glass sphere) instead" >&2
  exit 0
}
command -v node >/dev/null 2>&1 || fallback "node not found (apt-get install nodejs npm, or scripts/install-deps.sh)"
command -v npm >/dev/null 2>&1 || fallback "npm not found (apt-get install nodejs npm, or scripts/install-deps.sh)"
if [ ! -f "$prefix/node_modules/bunny/package.json" ] ||
   ! grep -q "\"version\": *\"$version\"" "$prefix/node_modules/bunny/package.json"; then
  mkdir -p "$prefix"
  npm install --prefix "$prefix" --no-audit --no-fund --no-save --fetch-retries=1 \
      --fetch-timeout=30000 "bunny@$version" >"$prefix/npm-install.log" 2>&1 ||
    fallback "npm install bunny@$version failed (see $prefix/npm-install.log)"
fi
node "$here/bunny_to_obj.js" "$prefix" "$out" || fallback "conversion failed"
echo "make_bunny_mesh: wrote $out"
