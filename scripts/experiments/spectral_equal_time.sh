#!/usr/bin/env bash
# Issue 9's figures: `nee` on scenes/droplet at equal time, before and after hero wavelengths,
# the sobol sampler and the render-loop work.
#  - the directly lit floor away from the caustic (crop FLOOR): per-pixel median error against
#    a long `bdpt` render of that crop (an independent technique);
#  - the whole image: relMSE against a long `mnee` render.
# Both sides render with the one-pixel box filter, as the reference does. The equal-time render is
# full-frame; its floor crop is then re-rendered at the spp it reached (pixels are a pure function
# of seed, pixel and sample index, so the crop equals that region of the full render).
# Usage: scripts/experiments/spectral_equal_time.sh [seconds=30] [floor reference spp=40000]
#        [whole-image reference seconds=480]
# SNELL_BEFORE=path/to/old/snell and SCENE_BEFORE=old/droplet.xml add the "before" rows (a
# snell built from the commit before this work, with its own copy of the scene file).
source "$(dirname "$0")/common.sh"
T=${1:-30}
REF_SPP=${2:-40000}
REF_T=${3:-480}
THREADS=${THREADS:-2}
FLOOR=${FLOOR:-470,360,140,110}
OUT=results/spectral_equal_time
mkdir -p "$OUT"

# crop_scene IN OUT: the scene with the film cropped to FLOOR.
crop_scene() {
  IFS=, read -r x y w h <<<"$FLOOR"
  sed "s|<integer name=\"height\" value=\"\$res_y\"/>|&<integer name=\"crop_offset_x\" value=\"$x\"/><integer name=\"crop_offset_y\" value=\"$y\"/><integer name=\"crop_width\" value=\"$w\"/><integer name=\"crop_height\" value=\"$h\"/>|" "$1" >"$2"
  grep -q crop_offset_x "$2" || { echo "could not crop $1" >&2; exit 1; }
}
spp_of() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['spp_reached'])" "$1"; }

SCENE=scenes/droplet/droplet.xml
crop_scene "$SCENE" "$OUT/floor.xml"
BOX=(-D rfilter=box)

if [ ! -f "$OUT/ref_floor.exr" ]; then
  "${LAUNCH[@]}" "$SNELL" render "$OUT/floor.xml" -D integrator=bdpt "${BOX[@]}" --spp "$REF_SPP" -t "$THREADS" -q --seed 7 \
    -o "$OUT/ref_floor.exr"
fi
if [ ! -f "$OUT/ref_full.exr" ]; then
  "${LAUNCH[@]}" "$SNELL" render "$SCENE" -D integrator=mnee "${BOX[@]}" --time "$REF_T" -t "$THREADS" -q --seed 7 -o "$OUT/ref_full.exr"
fi

# run NAME BINARY SCENE [defines...]: equal-time full frame, then its floor crop at the same spp.
run() {
  local name=$1 bin=$2 scene=$3
  shift 3
  "${LAUNCH[@]}" "$bin" render "$scene" -D integrator=nee "$@" --time "$T" -t "$THREADS" -q --seed 1 -o "$OUT/$name.exr"
  local spp
  spp=$(spp_of "$OUT/$name.json")
  crop_scene "$scene" "$OUT/${name}_floor.xml"
  "${LAUNCH[@]}" "$bin" render "$OUT/${name}_floor.xml" -D integrator=nee "$@" --spp "$spp" -t "$THREADS" -q --seed 1 \
    -o "$OUT/${name}_floor.exr"
  echo "== $name: $spp spp in $T s"
  "$SNELL" diff "$OUT/${name}_floor.exr" "$OUT/ref_floor.exr" | sed 's/^image /floor /'
  "$SNELL" diff "$OUT/$name.exr" "$OUT/ref_full.exr"
}

{
  echo "# nee on scenes/droplet, $T s on $THREADS threads (box filter); floor $FLOOR vs bdpt $REF_SPP spp, image vs mnee $REF_T s"
  if [ -n "${SNELL_BEFORE:-}" ]; then run before "$SNELL_BEFORE" "${SCENE_BEFORE:?set SCENE_BEFORE}"; fi
  run after_1wl "$SNELL" "$SCENE" "${BOX[@]}" -D spectral_samples=1 -D sampler=independent
  run after_indep "$SNELL" "$SCENE" "${BOX[@]}" -D sampler=independent
  run after "$SNELL" "$SCENE" "${BOX[@]}"
} | tee "$OUT/summary.txt"
