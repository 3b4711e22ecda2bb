#!/usr/bin/env bash
# Issue 29's "hslt converges to bdpt's image": the droplet (scenes/droplet) and the glass sphere
# (scenes/glass_sphere) at 160 x 120, hslt at growing mutation counts (a fixed-length hslt image
# is a pure function of the seed, whatever the thread count) against a bdpt reference of
# REF_SECONDS, and against a long mnee reference as a second, independent check (bdpt is weak on
# the droplet's caustic seen through the droplet, an SDS path). Prints, per render, relMSE /
# per-pixel median relative error / mean over the reference's, over the image and the caustic
# crops. Renders are cached in results/hslt_convergence/; delete a file to redo it.
# Usage: scripts/experiments/hslt_convergence.sh [REF_SECONDS=600] [MUTATIONS="256 1024 4096"]
# THREADS=n sets the thread count of every render (default: all cores).
source "$(dirname "$0")/common.sh"
REF_T=${1:-600}
MUTATIONS=${2:-"256 1024 4096"}
OUT=results/hslt_convergence
THREAD_ARGS=(); if [ -n "${THREADS:-}" ]; then THREAD_ARGS=(-t "$THREADS"); fi
mkdir -p "$OUT"
RES=(-D res_x=160 -D res_y=120)

render() {  # NAME SCENE INTEGRATOR ARGS...
  local name=$1 scene=$2 integ=$3; shift 3
  [ -f "$OUT/$name.exr" ] && return
  "${LAUNCH[@]}" "$SNELL" render "$scene" -D integrator="$integ" "${RES[@]}" "${THREAD_ARGS[@]}" -o "$OUT/$name.exr" -q "$@"
}

score() {  # IMAGE REFERENCE CROPS...
  local img=$1 ref=$2; shift 2
  local args=(); for c in "$@"; do args+=(--crop "$c"); done
  "$SNELL" diff --json "$img" "$ref" "${args[@]}" | python3 -c '
import json, sys
print(" | ".join("%.4g / %.3f / %.3f" % (c["rel_mse"], c["median_rel_error"], c["mean"] / c["mean_reference"])
                 for c in json.load(sys.stdin)))'
}

for scene in droplet glass_sphere; do
  if [ "$scene" = droplet ]; then
    file=scenes/droplet/droplet.xml; crops=(57,47,47,27 37,50,22,30); mnee_spp=4096
    what="image | transmitted caustic 57,47,47,27 | reflected caustic 37,50,22,30"
  else
    file=scenes/glass_sphere/glass_sphere.xml; crops=(87,97,47,22 47,23,67,63); mnee_spp=2048
    what="image | floor caustic 87,97,47,22 | cube through the glass 47,23,67,63"
  fi
  render "${scene}_bdpt" "$file" bdpt --time "$REF_T" --seed 21
  render "${scene}_mnee" "$file" mnee --spp "$mnee_spp" --seed 77
  for m in $MUTATIONS; do render "${scene}_hslt_$m" "$file" hslt --spp "$m" --seed 11; done
  echo "## $scene ($what; relMSE / median error / mean over the reference's)"
  echo "mnee ${mnee_spp} spp vs bdpt ${REF_T} s: $(score "$OUT/${scene}_mnee.exr" "$OUT/${scene}_bdpt.exr" "${crops[@]}")"
  for m in $MUTATIONS; do
    echo "hslt $m vs bdpt: $(score "$OUT/${scene}_hslt_$m.exr" "$OUT/${scene}_bdpt.exr" "${crops[@]}")"
    echo "hslt $m vs mnee: $(score "$OUT/${scene}_hslt_$m.exr" "$OUT/${scene}_mnee.exr" "${crops[@]}")"
  done
done
