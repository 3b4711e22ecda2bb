#!/usr/bin/env bash
# Paper Table 1: the manifold walk on the off-centre caustic of Fig. 4 (scenes/offcentre_caustic)
# with max_iterations 5, 10, 20, 35, 50, without (A) and with (B) allow_error_increase: seconds in
# walks, mean iterations of successful walks and success rate (stats JSON `extra.mnee`).
# Every run renders the same samples, so times are comparable: the budget is samples per pixel.
# Output: results/table1_iterations/ (summary.md, t1_<iterations>_<A|B>.{exr,png,json}).
# Usage: scripts/experiments/table1_iterations.sh [spp=16]
# Extra defines: SNELL_DEFINES="res_x=160 res_y=120".
source "$(dirname "$0")/common.sh"
SPP=${1:-16}
OUT=results/table1_iterations
SCENE=scenes/offcentre_caustic/offcentre_caustic.xml
rm -rf "$OUT"; mkdir -p "$OUT"

for it in 5 10 20 35 50; do
  for var in A B; do
    inc=false; [ $var = B ] && inc=true
    echo "== max_iterations $it, variant $var"
    "${LAUNCH[@]}" "$SNELL" render "$SCENE" -D max_iterations=$it -D allow_error_increase=$inc --spp "$SPP" --seed 3 \
      -o "$OUT/t1_${it}_$var.exr" -q "${DEFINES[@]}"
  done
done
python3 scripts/experiments/summarize.py table1 "$OUT" \
  "Table 1: walk iterations on the off-centre caustic (scenes/offcentre_caustic), $SPP spp"
echo "![50 iterations, B](t1_50_B.png)" >> "$OUT/summary.md"
cat "$OUT/summary.md"
