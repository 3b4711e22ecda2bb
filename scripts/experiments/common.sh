# Shared by the experiment scripts (sourced, not run). Sets SNELL (the Release binary, built
# with `make release` when missing; override with SNELL=path), DEFINES (an array of -D options
# from SNELL_DEFINES="name=value ...", e.g. SNELL_DEFINES="res_x=160 res_y=120" for a smoke
# test), LAUNCH (an array: the launcher every render and compare runs under, from SNELL_LAUNCH,
# e.g. SNELL_LAUNCH="mpirun -n 4"; docs/distributed.md) and has_compare (whether this snell has
# the `compare` command).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
SNELL=${SNELL:-build-release/snell}
if [ ! -x "$SNELL" ]; then make release >/dev/null; fi
DEFINES=()
# shellcheck disable=SC2206  # the launcher is a command line, split on spaces on purpose
LAUNCH=(${SNELL_LAUNCH:-})
for d in ${SNELL_DEFINES:-}; do DEFINES+=(-D "$d"); done

has_compare() { "$SNELL" --help 2>/dev/null | grep -qE "^ +compare "; }

# define_value NAME DEFAULT: the value SNELL_DEFINES gives NAME, else DEFAULT.
define_value() {
  local d
  for d in ${SNELL_DEFINES:-}; do
    if [ "${d%%=*}" = "$1" ]; then echo "${d#*=}"; return; fi
  done
  echo "$2"
}

# scale_crop X,Y,W,H: a crop given on the 640x480 film, scaled to the film in use.
scale_crop() {
  local rx ry
  rx=$(define_value res_x 640); ry=$(define_value res_y 480)
  python3 -c "import sys; x,y,w,h=map(int,sys.argv[1].split(',')); sx=$rx/640; sy=$ry/480; print('%d,%d,%d,%d'%(x*sx,y*sy,max(1,w*sx),max(1,h*sy)))" "$1"
}
