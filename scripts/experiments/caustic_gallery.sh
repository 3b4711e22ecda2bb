#!/usr/bin/env bash
# The caustic gallery (issue 26): every case of scenes/caustics/gallery.tsv rendered at equal
# time with `nee`, the paper's estimator (`mnee-paper`: solutions=one), the default `mnee` and
# `mnee-biased`, each scored on its caustic crop against a reference (gallery.tsv's technique,
# `bdpt` where it converges, on the crop, cached), as one `snell compare` report per case and one
# table for the gallery.
# Usage:
#   caustic_gallery.sh reference [seconds per case=600]   results/gallery/ref/<case>.exr, cached:
#       rendered again only when the scene file, its defines, the crop, the reference technique
#       or the seconds change (the key beside it says which)
#   caustic_gallery.sh refcheck [seconds=300]            each reference's own noise: a second one
#       (seed 78) scored against it; with the first's time T its own relMSE is about the figure
#       printed x SECONDS / (SECONDS + T)
#   caustic_gallery.sh refmean [seconds=120]             each reference's crop mean against two
#       path-traced renders of the crop (seeds 81, 82): the check of an MNEE reference
#   caustic_gallery.sh run LABEL [seconds=30]            results/gallery/LABEL/<case>/report.html
#       for each case, then the table of every case LABEL holds (results/gallery/LABEL/table.md)
#   caustic_gallery.sh table LABEL                       the table again from the reports
#   caustic_gallery.sh seeds LABEL [N=4] [seconds=30]    `run` with seeds 1..N (LABEL/seed1 ...),
#       then `seedtable`: one 30 s run is one draw of a heavy-tailed error, and its crop mean
#       wanders by 1-2 % from seed to seed (docs/experiments.md, ninth measurement)
#   caustic_gallery.sh seedtable LABEL                   per case and technique, over the runs in
#       LABEL/seed*: relMSE and median error averaged, the crop mean's average, spread (standard
#       deviation over the runs, divided by their number) and worst seed, the runs whose mean lies
#       within 2 % (LABEL/seeds.md)
#   caustic_gallery.sh pairs LABEL_A LABEL_B               each technique's own relMSE, without the
#       reference's noise: two runs of it with different seeds (e.g. LABEL/seed1, LABEL/seed2) give
#       E[(A - B)^2] = 2 Var per pixel, so half their relMSE (the reference only in the denominator,
#       --normalise-by) is one run's, where a technique is unbiased; the ratio of two techniques'
#       figures is then free of the reference's own error, which caps what `table` can show (the
#       pool's caustic near 1/30,000 of `nee`'s) (LABEL_A/pairs.md)
#   caustic_gallery.sh variant LABEL NAME 'XML' [seconds=30]   `mnee` (VARIANT_OF=nee: `nee`) with integrator parameters
#       XML (e.g. '<float name="connect_probability" value="0.3"/>') on every case, scored on its
#       crop like the table: results/gallery/LABEL/<case>_NAME.exr, a row each in variants.md
# CASES="ball_plane pool" limits the cases; TECHNIQUES (nee,mnee-paper,mnee,mnee-biased) the
# techniques compared; REF_INTEGRATOR overrides the manifest's reference technique (bdpt, pt,
# or mnee-paper / mnee-trials / mnee-all where no path-space technique converges; gallery.tsv
# says why);
# THREADS (2); SEED (1) the compared renders' seed; SNELL=path another build;
# SNELL_LAUNCH="cmd" runs every snell under cmd.
source "$(dirname "$0")/common.sh"
MODE=${1:?reference, refcheck, run or table}
THREADS=${THREADS:-2}
SEED=${SEED:-1}
TECHNIQUES=${TECHNIQUES:-nee,mnee-paper,mnee,mnee-biased}
VARIANT_OF=${VARIANT_OF:-mnee}  # the integrator a variant changes
GALLERY=scenes/caustics
OUT=results/gallery
mkdir -p "$OUT/ref"

# The manifest: case, scene, defines (comma-separated or -), crop.
declare -A SCENE DEFS CROP REF
ORDER=()
while IFS=$'\t' read -r c scene defs crop ref; do
  [ -z "$c" ] || [ "${c:0:1}" = "#" ] && continue
  SCENE[$c]=$GALLERY/$scene; DEFS[$c]=$defs; CROP[$c]=$crop; REF[$c]=${REF_INTEGRATOR:-${ref:-bdpt}}; ORDER+=("$c")
done <"$GALLERY/gallery.tsv"
read -r -a CASES <<<"${CASES:-${ORDER[*]}}"
for c in "${CASES[@]}"; do [ -n "${SCENE[$c]:-}" ] || { echo "caustic_gallery: no case '$c' in $GALLERY/gallery.tsv" >&2; exit 2; }; done

# -D options of a case.
defines_of() {
  local d
  [ "${DEFS[$1]}" = - ] && return
  IFS=, read -r -a d <<<"${DEFS[$1]}"
  for x in "${d[@]}"; do printf -- '-D %s ' "$x"; done
}
# The scene with its film cropped to X,Y,W,H (the reference covers the caustic crop alone), its
# relative file names made absolute (it is written elsewhere).
with_crop() {
  local dir
  dir=$(cd "$(dirname "$1")" && pwd)
  IFS=, read -r x y w h <<<"$3"
  sed -e "s|<integer name=\"height\" value=\"\$res_y\"/>|&<integer name=\"crop_offset_x\" value=\"$x\"/><integer name=\"crop_offset_y\" value=\"$y\"/><integer name=\"crop_width\" value=\"$w\"/><integer name=\"crop_height\" value=\"$h\"/>|" \
    -e "s|name=\"filename\" value=\"\([^/\"][^\"]*\)\"|name=\"filename\" value=\"$dir/\1\"|" "$1" >"$2"
  grep -q crop_offset_x "$2" || { echo "caustic_gallery: could not crop $1" >&2; exit 1; }
}
# What a reference depends on: the scene file and the files it names, defines, crop, technique, time.
ref_key() {
  local c=$1 scene=${SCENE[$1]} f files=()
  for f in $(sed -n 's/.*name="filename" value="\([^"]*\)".*/\1/p' "$scene"); do files+=("$(dirname "$scene")/$f"); done
  { cat "$scene" "${files[@]}" 2>/dev/null; echo "${DEFS[$c]} ${CROP[$c]} ${REF[$c]} $2"; } | sha256sum | cut -c1-16
}
# with_integrator FILE TECHNIQUE: the scene file made ready for TECHNIQUE (mnee-all: mnee with
# every solution 16 surface trials find, walked everywhere; mnee-paper: the paper's estimator,
# solutions=one, walked everywhere; mnee-trials: the unbiased estimator walked everywhere, with
# surface trials beside failed straight walks too); prints the integrator type to render it with.
with_integrator() {
  case $2 in
    mnee-all)
      sed -i "s|<integer name=\"max_depth\" value=\"\$max_depth\"/>|&<string name=\"solutions\" value=\"all\"/><integer name=\"trials\" value=\"16\"/><string name=\"allocation\" value=\"fixed\"/>|" "$1"
      echo mnee ;;
    mnee-paper)
      sed -i "s|<integer name=\"max_depth\" value=\"\$max_depth\"/>|&<string name=\"solutions\" value=\"one\"/>|" "$1"
      echo mnee ;;
    mnee-trials)
      sed -i "s|<integer name=\"max_depth\" value=\"\$max_depth\"/>|&<string name=\"allocation\" value=\"fixed\"/><float name=\"failed_walk_weight\" value=\"1\"/>|" "$1"
      echo mnee ;;
    *) echo "$2" ;;
  esac
}
# render_crop CASE TECHNIQUE SECONDS SEED NAME: the case's caustic crop alone, rendered with
# TECHNIQUE into $OUT/ref/NAME.exr.
render_crop() {
  local integ
  with_crop "${SCENE[$1]}" "$OUT/ref/$5.xml" "${CROP[$1]}"
  integ=$(with_integrator "$OUT/ref/$5.xml" "$2")
  # shellcheck disable=SC2046
  "${LAUNCH[@]}" "$SNELL" render "$OUT/ref/$5.xml" $(defines_of "$1") -D integrator="$integ" --time "$3" \
    -t "$THREADS" -q --seed "$4" -o "$OUT/ref/$5.exr"
}
skip_missing() {  # a case whose build-time mesh is absent (no node/npm at build time) is skipped, loudly
  local f
  for f in $(sed -n 's/.*name="filename" value="\([^"]*\)".*/\1/p' "${SCENE[$1]}"); do
    [ -e "$(dirname "${SCENE[$1]}")/$f" ] || { echo "caustic_gallery: SKIP $1: $f is missing (made at build time, needs node)" >&2; return 0; }
  done
  return 1
}

case $MODE in
reference)
  T=${2:-600}
  for c in "${CASES[@]}"; do
    skip_missing "$c" && continue
    key=$(ref_key "$c" "$T")
    if [ -f "$OUT/ref/$c.exr" ] && [ "$(cat "$OUT/ref/$c.key" 2>/dev/null)" = "$key" ]; then
      echo "caustic_gallery: $c: reference cached ($OUT/ref/$c.exr)"; continue
    fi
    render_crop "$c" "${REF[$c]}" "$T" 77 "$c"
    echo "$key" >"$OUT/ref/$c.key"
  done
  ;;
refcheck)
  T=${2:-300}
  for c in "${CASES[@]}"; do
    [ -f "$OUT/ref/$c.exr" ] || continue
    render_crop "$c" "${REF[$c]}" "$T" 78 "${c}_check"
    "$SNELL" diff "$OUT/ref/${c}_check.exr" "$OUT/ref/$c.exr" | grep "^image" | sed "s|^image|$c reference check|"
  done
  ;;
refmean)
  T=${2:-120}
  for c in "${CASES[@]}"; do
    [ -f "$OUT/ref/$c.exr" ] || continue
    for s in 81 82; do
      render_crop "$c" pt "$T" "$s" "${c}_pt$s"
      "$SNELL" diff "$OUT/ref/${c}_pt$s.exr" "$OUT/ref/$c.exr" --json | python3 -c "import json,sys; m=json.load(sys.stdin)[0]; print('$c: pt (seed $s, ${T} s) crop mean / ${REF[$c]} reference %.4f' % (m['mean'] / m['mean_reference']))"
    done
  done
  ;;
run)
  LABEL=${2:?label}
  T=${3:-30}
  for c in "${CASES[@]}"; do
    skip_missing "$c" && continue
    [ -f "$OUT/ref/$c.exr" ] || { echo "caustic_gallery: $c has no reference: run '$0 reference' first" >&2; exit 1; }
    IFS=, read -r x y _ _ <<<"${CROP[$c]}"
    # shellcheck disable=SC2046
    "${LAUNCH[@]}" "$SNELL" compare "${SCENE[$c]}" $(defines_of "$c") --integrators "$TECHNIQUES" --time "$T" \
      -t "$THREADS" --seed "$SEED" --reference "$OUT/ref/$c.exr" --reference-offset "$x,$y" \
      --convergence-steps 0 -q -o "$OUT/$LABEL/$c" >/dev/null
  done
  # The table covers every case of the label, those of earlier runs too.
  CASES="" "$0" table "$LABEL"
  ;;
table)
  LABEL=${2:?label}
  python3 - "$OUT/$LABEL" "${CASES[@]}" <<'EOF' | tee "$OUT/$LABEL/table.md"
import json, os, sys
root, cases = sys.argv[1], sys.argv[2:]
rows = []
for c in cases:
    p = os.path.join(root, c, "report.json")
    if not os.path.exists(p):
        continue
    rep = json.load(open(p))
    its = rep["integrators"]
    nee = next((i for i in its if i["name"] == "nee"), None)
    nee_ms = nee["seconds"] * 1000 / nee["spp_mean"] if nee and nee["spp_mean"] > 0 else None
    nee_rel = nee["metrics"][0]["rel_mse"] if nee else None
    for it in its:
        m = it["metrics"][0]  # the reference window: the case's caustic crop
        ms = it["seconds"] * 1000 / it["spp_mean"] if it["spp_mean"] > 0 else float("nan")
        ratio = m["mean"] / m["mean_reference"] if m["mean_reference"] > 0 else float("nan")
        rows.append((c, it["name"], m["rel_mse"], m["median_rel_error"], ratio, it["spp_mean"], ms,
                     ms / nee_ms if nee_ms else float("nan"),
                     nee_rel / m["rel_mse"] if nee_rel and m["rel_mse"] > 0 else float("nan")))
print("| case | technique | caustic relMSE | median error | mean / reference | spp | ms per spp | cost / nee's | nee's relMSE / this |")
print("|---|---|---|---|---|---|---|---|---|")
for r in rows:
    print("| %s | %s | %.4g | %.3f | %.3f | %.1f | %.0f | %.2f | %.3g |" % r)
EOF
  ;;
seeds)
  LABEL=${2:?label}
  N=${3:-4}
  T=${4:-30}
  for s in $(seq 1 "$N"); do
    SEED=$s CASES="${CASES[*]}" "$0" run "$LABEL/seed$s" "$T" >/dev/null
  done
  CASES="${CASES[*]}" "$0" seedtable "$LABEL"
  ;;
seedtable)
  LABEL=${2:?label}
  mkdir -p "$OUT/$LABEL"
  python3 - "$OUT/$LABEL" "${CASES[@]}" <<'EOF' | tee "$OUT/$LABEL/seeds.md"
import glob, json, math, os, sys
root, cases = sys.argv[1], sys.argv[2:]
runs = sorted(d for d in glob.glob(os.path.join(root, "seed*")) if os.path.isdir(d))
print("Over %d runs (%s)." % (len(runs), ", ".join(os.path.basename(r) for r in runs)))
print()
print("| case | technique | runs | caustic relMSE (average) | median error | mean / reference: average (sd; worst) "
      "| runs within 2 % | ms per spp | relMSE over nee's |")
print("|---|---|---|---|---|---|---|---|---|")
for c in cases:
    by = {}
    for r in runs:
        p = os.path.join(r, c, "report.json")
        if not os.path.exists(p):
            continue
        for it in json.load(open(p))["integrators"]:
            m = it["metrics"][0]  # the reference window: the case's caustic crop
            if not (m["mean_reference"] > 0 and it["spp_mean"] > 0):
                continue
            by.setdefault(it["name"], []).append((m["rel_mse"], m["median_rel_error"], m["mean"] / m["mean_reference"],
                                                  it["seconds"] * 1000 / it["spp_mean"]))
    avg = lambda xs: sum(xs) / len(xs)
    nee = avg([x[0] for x in by["nee"]]) if "nee" in by else None
    for name, xs in by.items():
        rel, med, means, ms = (avg([x[i] for x in xs]) for i in range(4))
        sd = math.sqrt(avg([(x[2] - means) ** 2 for x in xs]))
        worst = max((x[2] for x in xs), key=lambda v: abs(v - 1))
        within = sum(abs(x[2] - 1) <= 0.02 for x in xs)
        print("| %s | %s | %d | %.4g | %.3f | %.3f (%.3f; %.3f) | %d of %d | %.0f | %s |" % (
            c, name, len(xs), rel, med, means, sd, worst, within, len(xs), ms,
            "%.2f" % (rel / nee) if nee else "-"))
EOF
  ;;
pairs)
  A=${2:?first label}
  B=${3:?second label}
  {
    echo "| case | technique | own relMSE (half of $A against $B) | relMSE against the reference ($A / $B) | nee's own / this |"
    echo "|---|---|---|---|---|"
    for c in "${CASES[@]}"; do
      nee_own=""
      for t in nee mnee-paper mnee mnee-biased; do
        a=$OUT/$A/$c/$t.exr b=$OUT/$B/$c/$t.exr
        if [ ! -f "$a" ] || [ ! -f "$b" ]; then continue; fi
        own=$("$SNELL" diff "$a" "$b" --normalise-by "$OUT/ref/$c.exr" --json |
          python3 -c "import json,sys; print(json.load(sys.stdin)[0]['rel_mse'] / 2)")
        ra=$("$SNELL" diff "$a" "$OUT/ref/$c.exr" --json | python3 -c "import json,sys; print('%.4g' % json.load(sys.stdin)[0]['rel_mse'])")
        rb=$("$SNELL" diff "$b" "$OUT/ref/$c.exr" --json | python3 -c "import json,sys; print('%.4g' % json.load(sys.stdin)[0]['rel_mse'])")
        [ "$t" = nee ] && nee_own=$own
        ratio=$(python3 -c "print('%.4g' % ($nee_own / $own) if '$nee_own' and $own > 0 else '-')")
        printf '| %s | %s | %.4g | %s / %s | %s |\n' "$c" "$t" "$own" "$ra" "$rb" "$ratio"
      done
    done
  } | tee "$OUT/$A/pairs.md"
  ;;
variant)
  LABEL=${2:?label}
  NAME=${3:?variant name}
  XML=${4:?integrator parameters}
  T=${5:-30}
  mkdir -p "$OUT/$LABEL"
  for c in "${CASES[@]}"; do
    skip_missing "$c" && continue
    [ -f "$OUT/ref/$c.exr" ] || { echo "caustic_gallery: $c has no reference: run '$0 reference' first" >&2; exit 1; }
    IFS=, read -r x y w h <<<"${CROP[$c]}"
    # The variant beside the scene (its mesh paths stay valid), removed afterwards.
    scene="$(dirname "${SCENE[$c]}")/.variant_$$.xml"
    sed "s|<integer name=\"max_depth\" value=\"\$max_depth\"/>|&$XML|" "${SCENE[$c]}" >"$scene"
    # shellcheck disable=SC2046
    "${LAUNCH[@]}" "$SNELL" render "$scene" $(defines_of "$c") -D integrator="$VARIANT_OF" --time "$T" -t "$THREADS" -q \
      --seed "$SEED" -o "$OUT/$LABEL/${c}_$NAME.exr" || { rm -f "$scene"; exit 1; }
    rm -f "$scene"
    python3 - "$SNELL" "$OUT/$LABEL/${c}_$NAME.exr" "$OUT/ref/$c.exr" "$x,$y" "$x,$y,$w,$h" "$c" "$NAME" "$VARIANT_OF" <<'EOF' | tee -a "$OUT/$LABEL/variants.md"
import json, subprocess, sys
snell, img, ref, off, crop, case, name, integ = sys.argv[1:]
m = json.loads(subprocess.check_output([snell, "diff", img, ref, "--reference-offset", off, "--crop", crop, "--json"]))[1]
st = json.load(open(img[:-4] + ".json"))
spp = st.get("spp_mean", st.get("spp_reached"))
ms = st["seconds"] * 1000 / spp if spp else float("nan")
print("| %s | %s %s | %.4g | %.3f | %.3f | %.1f | %.0f |" % (case, integ, name, m["rel_mse"], m["median_rel_error"],
      m["mean"] / m["mean_reference"], spp, ms))
EOF
  done
  ;;
*)
  echo "caustic_gallery: unknown mode '$MODE' (reference, refcheck, refmean, run, table, seeds, seedtable, pairs, variant)" >&2; exit 2 ;;
esac
