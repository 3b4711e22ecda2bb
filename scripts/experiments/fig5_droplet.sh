#!/usr/bin/env bash
# Paper Fig. 5: equal-time comparison on the droplet (scenes/droplet) of the paper's techniques,
# pt, nee, bdpt, pssmlt(nee), pssmlt(mnee), erpt, hslt, mnee and mnee(biased), against a long mnee
# reference; relMSE and PSNR over the image and over the transmitted (under the droplet) and
# reflected (left of it) caustics. Output: results/fig5_droplet/ (summary.md, and the
# `snell compare` HTML report in report/). INTEGRATORS=a,b,... picks a subset.
# Usage: scripts/experiments/fig5_droplet.sh [seconds per integrator=5] [reference seconds=12x]
# Extra defines: SNELL_DEFINES="res_x=160 res_y=120" (crops scale with the film).
source "$(dirname "$0")/common.sh"
T=${1:-5}
REF_T=${2:-$(python3 -c "print($T*12)")}
OUT=results/fig5_droplet
SCENE=scenes/droplet/droplet.xml
TRANSMITTED=$(scale_crop 230,190,190,110)
REFLECTED=$(scale_crop 150,200,90,120)
INTEGRATORS=${INTEGRATORS:-"pt,nee,bdpt,pssmlt(nee),pssmlt(mnee),erpt,hslt,mnee,mnee(biased)"}
rm -rf "$OUT"; mkdir -p "$OUT"

"${LAUNCH[@]}" "$SNELL" compare "$SCENE" --integrators "$INTEGRATORS" --time "$T" \
  --reference-integrator mnee --reference-time "$REF_T" --crop "$TRANSMITTED" --crop "$REFLECTED" \
  --seed 1 --convergence-steps 3 -o "$OUT/report" "${DEFINES[@]}"
python3 scripts/experiments/summarize.py equal_time "$OUT" "Fig. 5: droplet, equal time ${T} s (reference: mnee ${REF_T} s)" \
  "transmitted caustic $TRANSMITTED" "reflected caustic $REFLECTED"
cat "$OUT/summary.md"
