#!/usr/bin/env bash
# Fails (and prints file:line of each violation) when the folders of src/ stop being layers:
#   1. a folder of src/ is missing from LAYERS below;
#   2. an #include "folder/..." in src/ runs from a lower layer to a higher one, or between two
#      peers of one layer;
#   3. a library snell_<folder> (cmake/*.cmake) compiles a source from another folder, or a
#      source is compiled into two libraries or into none;
#   4. target_link_libraries(snell_<folder> ...) links a library of the same or a higher layer.
# Registered with ctest as style.layers, so `make test` (and CI) checks it. Bash and POSIX awk
# only (mawk or gawk), like the other scripts. A new folder goes into LAYERS first.
set -euo pipefail
cd "$(dirname "$0")/.."

# Lowest first. Folders on one line are peers: they may include and link only lower lines.
LAYERS=(
  "core"
  "io"                     # file formats only: images, meshes, stats JSON
  "sampler camera geometry"
  "texture"                # Mitsuba's textures, looked up at a SurfaceInteraction
  "bsdf light"
  "scene"                  # Scene: shapes, Embree, lights, camera (no integrator)
  "manifold"
  "render"
  "integrators"
  "loader"                 # XML parser and loader, LoadedScene (which holds the integrator)
  "report"                 # `snell compare` reports; apps/ sit on top of everything
)

ranks=""
for i in "${!LAYERS[@]}"; do
  for folder in ${LAYERS[$i]}; do ranks+="$folder=$i "; done
done

status=0

# 1. Every folder of src/ has a layer.
for dir in src/*/; do
  folder=$(basename "$dir")
  case " $ranks" in
    *" $folder="*) ;;
    *) echo "src/$folder/: not in LAYERS of scripts/check-layers.sh"; status=1 ;;
  esac
done

# 2. Includes.
mapfile -t sources < <(find src -type f \( -name '*.h' -o -name '*.hpp' -o -name '*.cpp' -o -name '*.inl' \) | sort)
awk -v ranks="$ranks" '
  BEGIN {
    n = split(ranks, kv, " ")
    for (i = 1; i <= n; i++) { split(kv[i], p, "="); rank[p[1]] = p[2] + 0 }
  }
  /^[ \t]*#[ \t]*include[ \t]*"/ {
    inc = $0
    sub(/^[^"]*"/, "", inc)
    sub(/".*$/, "", inc)
    slash = index(inc, "/")
    if (slash == 0) next
    to = substr(inc, 1, slash - 1)
    if (!(to in rank)) next  # not a folder of src/
    from = FILENAME
    sub(/^src\//, "", from)
    from = substr(from, 1, index(from, "/") - 1)
    if (from == to || !(from in rank)) next
    if (rank[to] > rank[from]) {
      printf "%s:%d: %s includes \"%s\", a higher layer (%s above %s)\n", FILENAME, FNR, from, inc, to, from
      bad = 1
    } else if (rank[to] == rank[from]) {
      printf "%s:%d: %s includes \"%s\", a peer on the same layer (%s, %s)\n", FILENAME, FNR, from, inc, from, to
      bad = 1
    }
  }
  END { exit bad }
' "${sources[@]}" || status=1

# 3 and 4. Libraries and their links, from snell_library(...) and target_link_libraries(...)
# calls (possibly spanning several lines) in CMakeLists.txt and cmake/*.cmake.
awk -v ranks="$ranks" '
  BEGIN {
    n = split(ranks, kv, " ")
    for (i = 1; i <= n; i++) { split(kv[i], p, "="); rank[p[1]] = p[2] + 0 }
  }
  NR == FNR { cpp[$0] = 1; next }  # first input: every .cpp under src/
  {
    line = $0
    sub(/#.*$/, "", line)
    if (depth == 0) {
      if (line ~ /^[ \t]*(snell_library|target_link_libraries)[ \t]*\(/) {
        call = line; at = FILENAME ":" FNR; depth = 0
      } else next
    } else call = call " " line
    o = gsub(/\(/, "(", line); c = gsub(/\)/, ")", line)
    depth += o - c
    if (depth > 0) next
    depth = 0
    check(call, at)
  }
  function folder_of(lib) { return substr(lib, 7) }  # snell_<folder>
  function check(call, at,    kind, t, nt, i, lib, f, src, dep) {
    kind = call; sub(/[ \t]*\(.*$/, "", kind); sub(/^[ \t]*/, "", kind)
    sub(/^[^(]*\(/, "", call); sub(/\)[^)]*$/, "", call)
    nt = split(call, t, /[ \t]+/)
    i = 1
    while (i <= nt && t[i] == "") i++
    lib = t[i]
    if (lib !~ /^snell_/) return
    f = folder_of(lib)
    if (kind == "snell_library") {
      if (!(f in rank)) { printf "%s: library %s matches no folder in LAYERS\n", at, lib; bad = 1; return }
      for (i++; i <= nt; i++) {
        src = t[i]
        sub(/^\$\{PROJECT_SOURCE_DIR\}\//, "", src)
        if (src !~ /^src\//) continue
        if (substr(src, 5, length(f) + 1) != f "/") {
          printf "%s: %s compiles %s, outside src/%s/\n", at, lib, src, f; bad = 1
        }
        if (src in owner) { printf "%s: %s is compiled into %s and %s\n", at, src, owner[src], lib; bad = 1 }
        owner[src] = lib
      }
    } else if (f in rank) {  # target_link_libraries of a layer library
      for (i++; i <= nt; i++) {
        dep = t[i]
        if (dep !~ /^snell_/ || !(folder_of(dep) in rank)) continue
        if (rank[folder_of(dep)] >= rank[f] && dep != lib) {
          printf "%s: %s links %s, on the same or a higher layer\n", at, lib, dep; bad = 1
        }
      }
    }
  }
  END {
    for (src in cpp) if (!(src in owner)) { printf "%s: compiled into no snell_<folder> library\n", src; bad = 1 }
    exit bad
  }
' <(find src -type f -name '*.cpp' | sort) CMakeLists.txt cmake/*.cmake || status=1

if [ $status -ne 0 ]; then
  echo "check-layers: the layer order is broken (lowest first):"
  printf '  %s\n' "${LAYERS[@]}"
  exit 1
fi
echo "check-layers: every include and library link runs downwards"
