#!/usr/bin/env bash
# Paper Fig. 8: the droplet at Beckmann alpha 0.01, 0.05, 0.1, 0.2, 0.5 (droplet.xml -D alpha=...),
# nee against mnee at equal time, each against a long mnee reference at the same alpha.
# Output: results/fig8_roughness/ (summary.md; alpha_<a>/report/ per roughness).
# Usage: scripts/experiments/fig8_roughness.sh [seconds per integrator=2] [reference seconds=12x]
# Extra defines: SNELL_DEFINES="res_x=160 res_y=120".
source "$(dirname "$0")/common.sh"
T=${1:-2}
REF_T=${2:-$(python3 -c "print($T*12)")}
OUT=results/fig8_roughness
SCENE=scenes/droplet/droplet.xml
ALPHAS=(0.01 0.05 0.1 0.2 0.5)
rm -rf "$OUT"; mkdir -p "$OUT"

for a in "${ALPHAS[@]}"; do
  dir=$OUT/alpha_$a/report
  echo "== alpha $a"
  if has_compare; then
    "${LAUNCH[@]}" "$SNELL" compare "$SCENE" --integrators nee,mnee --time "$T" --reference-integrator mnee \
      --reference-time "$REF_T" --seed 1 -o "$dir" -q -D alpha=$a "${DEFINES[@]}"
  else
    mkdir -p "$dir"
    "${LAUNCH[@]}" "$SNELL" render "$SCENE" -D alpha=$a -D integrator=mnee --time "$REF_T" --seed 999 -o "$dir/reference.exr" -q "${DEFINES[@]}"
    for integ in nee mnee; do
      "${LAUNCH[@]}" "$SNELL" render "$SCENE" -D alpha=$a -D integrator=$integ --time "$T" --seed 1 -o "$dir/$integ.exr" -q "${DEFINES[@]}"
      "$SNELL" diff --json "$dir/$integ.exr" "$dir/reference.exr" > "$dir/$integ.diff.json"
    done
  fi
done
python3 scripts/experiments/summarize.py roughness "$OUT" \
  "Fig. 8: droplet roughness sweep, nee vs mnee, equal time ${T} s (reference: mnee ${REF_T} s)" "${ALPHAS[@]}"
cat "$OUT/summary.md"
