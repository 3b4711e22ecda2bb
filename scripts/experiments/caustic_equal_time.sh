#!/usr/bin/env bash
# Issue 10's figures: `nee`, `mnee`, `mnee biased=true` (and `mnee solutions=unbiased` with
# INTEGRATORS="nee mnee mnee_biased mnee_unbiased") at equal time on caustics, scored
# against an independent reference (`bdpt`, rendered on the scored crops only).
#   cases: droplet_a002 (scenes/droplet, alpha 0.02), glass_sphere (smooth glass around a cube)
#   crops: droplet caustic seen through the droplet; the glass sphere's floor caustic and its cube
# Usage:
#   caustic_equal_time.sh reference [seconds per case=2400]   results/caustics/ref_<case>.exr
#   caustic_equal_time.sh render LABEL [seconds=30]            results/caustics/LABEL/<case>_<integ>.exr
#   caustic_equal_time.sh score LABEL                          a table per case and crop
#   caustic_equal_time.sh noise LABEL1 LABEL2                 each technique's own noise: LABEL2
#       rendered like LABEL1 with another SEED, scored against LABEL1 with relMSE's denominators
#       from the reference (`snell diff --normalise-by`, so that no noisy render divides); for two
#       independent renders of equal variance the figure is twice either's relMSE, and half of it
#       is printed (the technique's relMSE at that time, its bias left out, the reference's noise
#       only in the denominators)
#   caustic_equal_time.sh compare LABEL [seconds=30]           `snell compare` of nee, mnee and
#       mnee-biased (the issue's command), each case scored on its crops against the crop
#       reference (--reference-offset): results/caustics/LABEL/compare_<case>/report.html
#   caustic_equal_time.sh refcheck [seconds=600]               the references' own noise: a second
#       reference (seed 78) for SECONDS, scored against the first; with the first's time T, the
#       first's own relMSE is about that figure x SECONDS / (SECONDS + T)
# CASES="droplet_a002" (say) limits the cases; droplet_smooth is the droplet with alpha 0.
# SNELL=path/to/snell renders with another build (e.g. the one before issue 10); THREADS (2);
# SEED (1) the renders' seed.
source "$(dirname "$0")/common.sh"
MODE=${1:?reference, render, compare, score, noise or refcheck}
THREADS=${THREADS:-2}
SEED=${SEED:-1}
OUT=results/caustics
mkdir -p "$OUT"

read -r -a CASES <<<"${CASES:-droplet_a002 glass_sphere droplet_smooth}"
scene_of() { case $1 in droplet_*) echo scenes/droplet/droplet.xml ;; glass_sphere) echo scenes/glass_sphere/glass_sphere.xml ;; esac; }
defines_of() { case $1 in droplet_a002) echo "-D alpha=0.02" ;; droplet_smooth) echo "-D alpha=0" ;; *) echo "" ;; esac; }
# The reference covers the union of a case's crops (x,y,w,h on the case's own film).
ref_crop_of() { case $1 in droplet_*) echo 230,190,190,110 ;; glass_sphere) echo 140,70,260,285 ;; esac; }
crops_of() { case $1 in droplet_*) echo "caustic:230,190,190,110" ;; glass_sphere) echo "caustic:260,290,140,65 cube:140,70,200,190" ;; esac; }

# with_crop IN OUT X,Y,W,H: the scene with its film cropped.
with_crop() {
  IFS=, read -r x y w h <<<"$3"
  sed "s|<integer name=\"height\" value=\"\$res_y\"/>|&<integer name=\"crop_offset_x\" value=\"$x\"/><integer name=\"crop_offset_y\" value=\"$y\"/><integer name=\"crop_width\" value=\"$w\"/><integer name=\"crop_height\" value=\"$h\"/>|" "$1" >"$2"
  grep -q crop_offset_x "$2" || { echo "could not crop $1" >&2; exit 1; }
}
# with_params IN OUT XML: the scene with XML (parameters) added to its integrator.
with_params() {
  sed "s|<integer name=\"max_depth\" value=\"\$max_depth\"/>|&$3|" "$1" >"$2"
}
# The techniques compared; INTEGRATORS overrides (mnee_unbiased needs a snell with `solutions`).
INTEGRATORS=${INTEGRATORS:-nee mnee mnee_biased}
# Every technique `score` and `noise` look for.
ALL_TECHNIQUES="nee mnee mnee_biased mnee_paper mnee_paperbiased mnee_unbiased mnee_unbiased_biased mnee_reflections mnee_fallback mnee_fallback_biased mnee_sms"
params_of() {
  case $1 in
    mnee_biased) echo '<boolean name="biased" value="true"/>' ;;
    mnee_unbiased) echo '<string name="solutions" value="unbiased"/><string name="seeding" value="straight+surface"/>' ;;
    mnee_sms) echo '<string name="solutions" value="unbiased"/><float name="surface_weight" value="1"/>' ;;
    mnee_reflections) echo '<string name="solutions" value="unbiased"/><string name="seeding" value="straight+surface"/><boolean name="reflections" value="true"/><float name="surface_weight" value="1"/>' ;;
    mnee_unbiased_biased) echo '<string name="solutions" value="unbiased"/><string name="seeding" value="straight+surface"/><boolean name="biased" value="true"/>' ;;
    mnee_paper) echo '<string name="solutions" value="one"/>' ;;
    mnee_paperbiased) echo '<string name="solutions" value="one"/><boolean name="biased" value="true"/>' ;;
    mnee_fallback) echo '<string name="solutions" value="fallback"/>' ;;
    mnee_fallback_biased) echo '<string name="solutions" value="fallback"/><boolean name="biased" value="true"/>' ;;
    *) echo "" ;;
  esac
}

case $MODE in
reference)
  T=${2:-2400}
  for c in "${CASES[@]}"; do
    [ -f "$OUT/ref_$c.exr" ] && continue
    with_crop "$(scene_of "$c")" "$OUT/ref_$c.xml" "$(ref_crop_of "$c")"
    # shellcheck disable=SC2046
    "${LAUNCH[@]}" "$SNELL" render "$OUT/ref_$c.xml" $(defines_of "$c") -D integrator=bdpt --time "$T" -t "$THREADS" -q --seed 77 \
      -o "$OUT/ref_$c.exr"
  done
  ;;
refcheck)
  T=${2:-600}
  for c in "${CASES[@]}"; do
    [ -f "$OUT/ref_$c.exr" ] || continue
    IFS=, read -r rx ry _ _ <<<"$(ref_crop_of "$c")"
    with_crop "$(scene_of "$c")" "$OUT/ref2_$c.xml" "$(ref_crop_of "$c")"
    # shellcheck disable=SC2046
    "${LAUNCH[@]}" "$SNELL" render "$OUT/ref2_$c.xml" $(defines_of "$c") -D integrator=bdpt --time "$T" -t "$THREADS" -q --seed 78 \
      -o "$OUT/ref2_$c.exr"
    for crop in $(crops_of "$c"); do
      IFS=, read -r x y w h <<<"${crop#*:}"
      "$SNELL" diff "$OUT/ref2_$c.exr" "$OUT/ref_$c.exr" --crop "$((x - rx)),$((y - ry)),$w,$h" | grep "^crop" \
        | sed "s|^crop [0-9,]*|$c reference check ${crop%%:*}|"
    done
  done
  ;;
render)
  LABEL=${2:?label}
  T=${3:-30}
  mkdir -p "$OUT/$LABEL"
  for c in "${CASES[@]}"; do
    for integ in $INTEGRATORS; do
      scene=$(scene_of "$c"); name=${integ%%_*}
      if [ -n "$(params_of "$integ")" ]; then
        with_params "$scene" "$OUT/$LABEL/${c}_$integ.xml" "$(params_of "$integ")"
        scene="$OUT/$LABEL/${c}_$integ.xml"
      fi
      # shellcheck disable=SC2046
      "${LAUNCH[@]}" "$SNELL" render "$scene" $(defines_of "$c") -D integrator=$name --time "$T" -t "$THREADS" -q --seed "$SEED" \
        -o "$OUT/$LABEL/${c}_$integ.exr"
    done
  done
  ;;
compare)
  LABEL=${2:?label}
  T=${3:-30}
  for c in "${CASES[@]}"; do
    IFS=, read -r rx ry _ _ <<<"$(ref_crop_of "$c")"
    crop_args=()
    for crop in $(crops_of "$c"); do crop_args+=(--crop "${crop#*:}"); done
    # shellcheck disable=SC2046
    "${LAUNCH[@]}" "$SNELL" compare "$(scene_of "$c")" $(defines_of "$c") --integrators nee,mnee,mnee-biased --time "$T" \
      -t "$THREADS" --seed "$SEED" --reference "$OUT/ref_$c.exr" --reference-offset "$rx,$ry" "${crop_args[@]}" \
      --convergence-steps 0 -q -o "$OUT/$LABEL/compare_$c"
  done
  ;;
score)
  LABEL=${2:?label}
  for c in "${CASES[@]}"; do
    IFS=, read -r rx ry _ _ <<<"$(ref_crop_of "$c")"
    for integ in $ALL_TECHNIQUES; do
      img="$OUT/$LABEL/${c}_$integ.exr"
      [ -f "$img" ] || continue
      spp=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['spp_reached'])" "${img%.exr}.json")
      for crop in $(crops_of "$c"); do
        "$SNELL" diff "$img" "$OUT/ref_$c.exr" --reference-offset "$rx,$ry" --crop "${crop#*:}" | grep "^crop" \
          | sed "s|^crop [0-9,]*|$c $integ ${crop%%:*} ($spp spp)|"
      done
    done
  done
  ;;
noise)
  A=${2:?label}
  B=${3:?second label}
  for c in "${CASES[@]}"; do
    for integ in $ALL_TECHNIQUES; do
      a="$OUT/$A/${c}_$integ.exr" b="$OUT/$B/${c}_$integ.exr"
      [ -f "$a" ] && [ -f "$b" ] || continue
      IFS=, read -r rx ry _ _ <<<"$(ref_crop_of "$c")"
      for crop in $(crops_of "$c"); do
        "$SNELL" diff "$b" "$a" --reference-offset "$rx,$ry" --normalise-by "$OUT/ref_$c.exr" --crop "${crop#*:}" --json \
          | python3 -c "import json,sys; j=json.load(sys.stdin); m=j[1]; print('$c $integ ${crop%%:*}: relMSE %.4g (half of %.4g, %s against %s)' % (m['rel_mse'] / 2, m['rel_mse'], '$B', '$A'))"
      done
    done
  done
  ;;
esac
