#!/usr/bin/env bash
# MNEE on the droplet (paper Fig. 5 / Table 1 set-up): an equal-time comparison of nee and mnee
# against a long reference, the Table 1 iteration sweep, and the share of the caustic that MNEE
# finds versus what MIS recovers through BSDF sampling. Output: results/mnee_droplet/.
# Usage: scripts/experiments/mnee_droplet.sh [equal_time_seconds=60] [reference_seconds=420]
# (SNELL_LAUNCH="mpirun -n 4" runs every render under that launcher).
set -euo pipefail
cd "$(dirname "$0")/../.."
T=${1:-60}
REF_T=${2:-420}
SNELL=build-release/snell
OUT=results/mnee_droplet
mkdir -p "$OUT"
[ -x "$SNELL" ] || make release >/dev/null
# shellcheck disable=SC2206  # SNELL_LAUNCH="mpirun -n 4": a launcher for every render
LAUNCH=(${SNELL_LAUNCH:-})
SCENE=builtin:droplet
CAUSTIC=230,190,190,110  # transmitted caustic under the droplet (640x480 film)
REFLECTED=150,200,90,120 # faint reflected caustic at its left foot

echo "== reference: mnee, ${REF_T}s"
"${LAUNCH[@]}" $SNELL render $SCENE -D integrator=mnee --time "$REF_T" --seed 999 -o "$OUT/reference.exr" -q
for integ in nee mnee; do
  echo "== $integ, ${T}s"
  "${LAUNCH[@]}" $SNELL render $SCENE -D integrator=$integ --time "$T" --seed 1 -o "$OUT/equal_time_$integ.exr" -q
  $SNELL diff "$OUT/equal_time_$integ.exr" "$OUT/reference.exr" --crop $CAUSTIC --crop $REFLECTED | tee "$OUT/equal_time_$integ.txt"
  python3 -c "import json;d=json.load(open('$OUT/equal_time_$integ.json'));print('  spp reached', d['spp_reached'])"
done

echo "== Table 1: max iterations sweep (A: error must decrease, B: may increase), 32 spp, 320x240"
printf "%-6s %-4s %10s %10s %10s\n" iters var seconds avg_it success > "$OUT/table1.txt"
for it in 5 10 20 35 50; do
  for var in A B; do
    inc=false; [ $var = B ] && inc=true
    sed "s|<integer name=\"max_depth\" value=\"\$max_depth\"/>|<integer name=\"max_depth\" value=\"\$max_depth\"/><integer name=\"max_iterations\" value=\"$it\"/><boolean name=\"allow_error_increase\" value=\"$inc\"/>|" \
      scenes/droplet/droplet.xml > "$OUT/droplet_t1.xml"
    "${LAUNCH[@]}" $SNELL render "$OUT/droplet_t1.xml" -D res_x=320 -D res_y=240 --spp 32 --seed 3 -o "$OUT/t1_${it}_$var.exr" -q
    python3 - "$OUT/t1_${it}_$var.json" $it $var >> "$OUT/table1.txt" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); m = d["extra"]["mnee"]
print("%-6s %-4s %10.2f %10.2f %9.1f%%" % (sys.argv[2], sys.argv[3], m["walk_seconds"], m["mean_iterations_success"], 100 * m["success_rate"]))
PY
  done
done
cat "$OUT/table1.txt"

echo "== caustic energy: unbiased mnee vs biased (outlier removal), 128 spp"
"${LAUNCH[@]}" $SNELL render $SCENE -D integrator=mnee --spp 128 --seed 5 -o "$OUT/share_unbiased.exr" -q
sed 's|<integer name="max_depth" value="$max_depth"/>|<integer name="max_depth" value="$max_depth"/><boolean name="biased" value="true"/>|' \
  scenes/droplet/droplet.xml > "$OUT/droplet_biased.xml"
"${LAUNCH[@]}" $SNELL render "$OUT/droplet_biased.xml" --spp 128 --seed 5 -o "$OUT/share_biased.exr" -q
$SNELL diff "$OUT/share_biased.exr" "$OUT/share_unbiased.exr" --crop $CAUSTIC | tee "$OUT/share.txt"
