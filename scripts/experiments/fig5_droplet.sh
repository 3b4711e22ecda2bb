#!/usr/bin/env bash
# Paper Fig. 5: equal-time comparison on the droplet (scenes/droplet): path, nee, mnee and biased
# mnee against a long mnee reference; relMSE and PSNR over the image and over the transmitted
# (under the droplet) and reflected (left of it) caustics. Output: results/fig5_droplet/
# (summary.md; with `snell compare`, the HTML report in report/).
# Usage: scripts/experiments/fig5_droplet.sh [seconds per integrator=5] [reference seconds=12x]
# Extra defines: SNELL_DEFINES="res_x=160 res_y=120" (crops scale with the film).
source "$(dirname "$0")/common.sh"
T=${1:-5}
REF_T=${2:-$(python3 -c "print($T*12)")}
OUT=results/fig5_droplet
SCENE=scenes/droplet/droplet.xml
TRANSMITTED=$(scale_crop 230,190,190,110)
REFLECTED=$(scale_crop 150,200,90,120)
rm -rf "$OUT"; mkdir -p "$OUT"

if has_compare; then
  "$SNELL" compare "$SCENE" --integrators path,nee,mnee,mnee-biased --time "$T" \
    --reference-integrator mnee --reference-time "$REF_T" --crop "$TRANSMITTED" --crop "$REFLECTED" \
    --seed 1 --convergence-steps 3 -o "$OUT/report" "${DEFINES[@]}"
else
  mkdir -p "$OUT/report"
  sed 's|<integer name="max_depth" value="$max_depth"/>|&<boolean name="biased" value="true"/>|' "$SCENE" > "$OUT/droplet_biased.xml"
  "$SNELL" render "$SCENE" -D integrator=mnee --time "$REF_T" --seed 999 -o "$OUT/report/reference.exr" -q "${DEFINES[@]}"
  for integ in path nee mnee mnee-biased; do
    scene=$SCENE; def=(-D integrator=$integ)
    [ $integ = mnee-biased ] && { scene=$OUT/droplet_biased.xml; def=(-D integrator=mnee); }
    "$SNELL" render "$scene" "${def[@]}" --time "$T" --seed 1 -o "$OUT/report/$integ.exr" -q "${DEFINES[@]}"
    "$SNELL" diff --json "$OUT/report/$integ.exr" "$OUT/report/reference.exr" --crop "$TRANSMITTED" --crop "$REFLECTED" > "$OUT/report/$integ.diff.json"
  done
fi
python3 scripts/experiments/summarize.py equal_time "$OUT" "Fig. 5: droplet, equal time ${T} s (reference: mnee ${REF_T} s)" \
  "transmitted caustic $TRANSMITTED" "reflected caustic $REFLECTED"
cat "$OUT/summary.md"
