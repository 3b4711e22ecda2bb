#!/usr/bin/env bash
# End-to-end checks of the `snell` command (run by ctest): errors name file:line, Ctrl-C still
# writes the image, --time stops at the budget, the stats JSON is complete.
set -u
SNELL="$1"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail=0
check() { if ! eval "$2"; then echo "FAIL: $1"; fail=1; else echo "ok: $1"; fi; }

# A small valid scene.
cat > "$TMP/ok.xml" <<'XML'
<scene version="3.0.0">
  <integrator type="nee"/>
  <sensor type="perspective">
    <transform name="to_world"><lookat origin="0,0,4" target="0,0,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="48"/></film>
  </sensor>
  <shape type="sphere"><bsdf type="dielectric"/></shape>
  <emitter type="constant"><rgb name="radiance" value="1,1,1"/></emitter>
</scene>
XML

# 1. Malformed XML: the error names file:line.
printf '<scene version="3.0.0">\n  <shape type="sphere">\n</scene>\n' > "$TMP/bad.xml"
out=$("$SNELL" render "$TMP/bad.xml" -o "$TMP/bad.exr" -q 2>&1); rc=$?
check "malformed XML exits non-zero" "[ $rc -ne 0 ]"
check "malformed XML names file:line" "echo \"\$out\" | grep -q 'bad.xml:[0-9]'"

# 2. Unknown parameter: file:line and the element.
sed 's|<bsdf type="dielectric"/>|<bsdf type="dielectric"><float name="int_iorr" value="1.5"/></bsdf>|' "$TMP/ok.xml" > "$TMP/unk.xml"
out=$("$SNELL" render "$TMP/unk.xml" -o "$TMP/unk.exr" -q 2>&1); rc=$?
check "unknown parameter exits non-zero" "[ $rc -ne 0 ]"
check "unknown parameter names file:line and element" "echo \"\$out\" | grep -q 'unk.xml:7.*int_iorr'"

# 3. Missing mesh: the path is named.
sed 's|<shape type="sphere"><bsdf type="dielectric"/></shape>|<shape type="obj"><string name="filename" value="nowhere/missing.obj"/></shape>|' "$TMP/ok.xml" > "$TMP/mesh.xml"
out=$("$SNELL" render "$TMP/mesh.xml" -o "$TMP/mesh.exr" -q 2>&1); rc=$?
check "missing mesh exits non-zero" "[ $rc -ne 0 ]"
check "missing mesh names the path" "echo \"\$out\" | grep -q 'nowhere/missing.obj'"

# 4. A normal render writes EXR, PNG and a stats JSON with the promised fields.
"$SNELL" render "$TMP/ok.xml" -o "$TMP/ok.exr" --spp 4 -q; rc=$?
check "render succeeds" "[ $rc -eq 0 ]"
check "EXR, PNG and JSON written" "[ -s $TMP/ok.exr ] && [ -s $TMP/ok.png ] && [ -s $TMP/ok.json ]"
for key in seconds spp_reached paths_per_second rays_per_second discarded; do
  check "stats JSON has $key" "grep -q '\"$key\"' $TMP/ok.json"
done

# 5. --time stops near the budget and reports the spp reached.
"$SNELL" render "$TMP/ok.xml" -o "$TMP/timed.exr" --time 1 -q; rc=$?
check "timed render succeeds" "[ $rc -eq 0 ]"
check "timed render reports spp" "grep -q '\"spp_reached\": [1-9]' $TMP/timed.json"

# 6. Ctrl-C (SIGINT) still writes the partial image.
"$SNELL" render "$TMP/ok.xml" -o "$TMP/int.exr" --spp 100000000 -q &
pid=$!
sleep 1.5
kill -INT $pid
wait $pid; rc=$?
check "interrupted render exits 130" "[ $rc -eq 130 ]"
check "interrupted render wrote its image" "[ -s $TMP/int.exr ] && [ -s $TMP/int.png ]"
check "stats JSON says interrupted" "grep -q '\"interrupted\": true' $TMP/int.json"

# 7. -D overrides a <default>; an unknown -D is an error.
"$SNELL" render builtin:droplet -o "$TMP/d.exr" -D res_x=32 -D res_y=24 -D spp=1 -q; rc=$?
check "-D override renders" "[ $rc -eq 0 ] && grep -q '\"width\": 32' $TMP/d.json"

# 8. --strategies: bdpt writes one image per strategy (lengths 1..max_depth=2: 1 + 3 images).
"$SNELL" render builtin:droplet -o "$TMP/s.exr" -D integrator=bdpt -D max_depth=2 -D res_x=32 -D res_y=24 -D spp=1 --strategies -q; rc=$?
check "--strategies renders" "[ $rc -eq 0 ]"
check "--strategies writes per-strategy EXRs" "[ -s $TMP/s_d1_s0_t2.exr ] && [ -s $TMP/s_d2_s2_t1.exr ] && [ \$(ls $TMP/s_d*.exr | wc -l) -eq 4 ]"

# 9. snell diff against a reference rendered on a crop of the film: --reference-offset places it,
#    and the crop's pixels then match the full render exactly (pixels are a pure function of seed,
#    pixel and sample index), so the error is zero; a window that does not fit is an error.
sed 's|<integer name="height" value="48"/>|<integer name="height" value="48"/><integer name="crop_offset_x" value="10"/><integer name="crop_offset_y" value="6"/><integer name="crop_width" value="20"/><integer name="crop_height" value="12"/>|' "$TMP/ok.xml" > "$TMP/crop.xml"
"$SNELL" render "$TMP/crop.xml" -o "$TMP/crop.exr" --spp 4 -q
out=$("$SNELL" diff "$TMP/ok.exr" "$TMP/crop.exr" --reference-offset 10,6 --crop 12,8,6,4 2>&1); rc=$?
check "diff with --reference-offset succeeds" "[ $rc -eq 0 ]"
check "crop render equals that window of the full render" "echo \"\$out\" | grep -q '^image .*relMSE 0 '"
check "diff --crop in image coordinates" "echo \"\$out\" | grep -q '^crop 12,8,6,4 .*relMSE 0 '"
out=$("$SNELL" diff "$TMP/ok.exr" "$TMP/crop.exr" --reference-offset 50,40 2>&1); rc=$?
check "a reference window outside the image is an error" "[ $rc -ne 0 ] && echo \"\$out\" | grep -q 'does not fit'"
# The other way round: a crop render scored against the full render with --image-offset (the
# reference is cut to the crop; --crop in the reference's coordinates: 24,14 is 14,8 of the crop,
# and would lie outside it unshifted), exactly again.
out=$("$SNELL" diff "$TMP/crop.exr" "$TMP/ok.exr" --image-offset 10,6 --crop 24,14,6,4 2>&1); rc=$?
check "diff --image-offset: the crop render equals the reference's window" "[ $rc -eq 0 ] && echo \"\$out\" | grep -q '^image .*relMSE 0 ' && echo \"\$out\" | grep -q '^crop 24,14,6,4 .*relMSE 0 '"
out=$("$SNELL" diff "$TMP/crop.exr" "$TMP/ok.exr" --image-offset 30,40 2>&1); rc=$?
check "an image window outside the reference is an error" "[ $rc -ne 0 ] && echo \"\$out\" | grep -q 'does not fit'"
out=$("$SNELL" diff "$TMP/crop.exr" "$TMP/ok.exr" --image-offset 10 2>&1); rc=$?
check "a malformed --image-offset names the option" "[ $rc -ne 0 ] && echo \"\$out\" | grep -q 'image-offset must be x,y'"
out=$("$SNELL" diff "$TMP/crop.exr" "$TMP/ok.exr" --image-offset 10,6 --reference-offset 10,6 2>&1); rc=$?
check "--image-offset with --reference-offset is an error" "[ $rc -ne 0 ] && echo \"\$out\" | grep -q 'excludes'"
# Issue 12: crop rectangles are checked in 64 bits (x = 2147483647 overflowed int and crashed).
for crop in 2147483647,0,10,10 0,2147483647,1,1 2147483647,2147483647,2147483647,2147483647 -1,0,2,2 1,1,0,1; do
  out=$("$SNELL" diff "$TMP/ok.exr" "$TMP/crop.exr" --reference-offset 10,6 --crop $crop 2>&1); rc=$?
  check "diff --crop $crop is an error" "[ $rc -eq 1 ] && echo \"\$out\" | grep -q 'crop'"
done
out=$("$SNELL" diff "$TMP/ok.exr" "$TMP/ok.exr" --reference-offset 2147483647,0 2>&1); rc=$?
check "diff --reference-offset 2147483647,0 is an error" "[ $rc -eq 1 ] && echo \"\$out\" | grep -q 'does not fit'"
# --normalise-by: relMSE's denominators from a third image. Normalised by the reference itself it
# is the plain figure; by another image it differs; two full renders of different seeds, cut to a
# crop reference's window and normalised by it, compare; a normaliser of another size is an error.
"$SNELL" render "$TMP/ok.xml" -o "$TMP/ok2.exr" --spp 4 --seed 2 -q
relmse() { "$SNELL" diff "$@" | grep '^image' | sed 's/.*relMSE \([^ ]*\) .*/\1/'; }
plain=$(relmse "$TMP/ok2.exr" "$TMP/ok.exr")
check "diff --normalise-by the reference is the plain relMSE" "[ \"$plain\" = \"$(relmse "$TMP/ok2.exr" "$TMP/ok.exr" --normalise-by "$TMP/ok.exr")\" ]"
check "diff --normalise-by another image changes relMSE" "[ \"$plain\" != \"$(relmse "$TMP/ok2.exr" "$TMP/ok.exr" --normalise-by "$TMP/timed.exr" 2>/dev/null || echo err)\" ]"
out=$("$SNELL" diff "$TMP/ok2.exr" "$TMP/ok.exr" --reference-offset 10,6 --normalise-by "$TMP/crop.exr" --crop 12,8,6,4 2>&1); rc=$?
check "diff of two renders normalised by a crop reference" "[ $rc -eq 0 ] && echo \"\$out\" | grep -q '^crop 12,8,6,4 .*relMSE [0-9]'"
out=$("$SNELL" diff "$TMP/ok2.exr" "$TMP/ok.exr" --normalise-by "$TMP/crop.exr" 2>&1); rc=$?
check "a normaliser of another size is an error" "[ $rc -eq 1 ] && echo \"\$out\" | grep -q 'normalise-by'"
# With --image-offset the normaliser is the reference's size (cut with it) or the image's: both give
# the same figure; a third size is an error naming it.
a=$(relmse "$TMP/crop.exr" "$TMP/ok2.exr" --image-offset 10,6 --normalise-by "$TMP/ok.exr")
b=$(relmse "$TMP/crop.exr" "$TMP/ok2.exr" --image-offset 10,6 --normalise-by "$TMP/crop.exr")
check "diff --image-offset normalised by the reference's size or the image's agree" "[ -n \"$a\" ] && [ \"$a\" = \"$b\" ] && [ \"$a\" != 0 ]"
sed 's|<integer name="height" value="48"/>|<integer name="height" value="40"/>|' "$TMP/ok.xml" > "$TMP/short.xml"
"$SNELL" render "$TMP/short.xml" -o "$TMP/short.exr" --spp 1 -q
out=$("$SNELL" diff "$TMP/crop.exr" "$TMP/ok2.exr" --image-offset 10,6 --normalise-by "$TMP/short.exr" 2>&1); rc=$?
check "a normaliser of a third size with --image-offset is an error" "[ $rc -ne 0 ] && echo \"\$out\" | grep -q 'normalise-by'"

# 10. -a adds a folder to find the scene's files in (Mitsuba's -a), after the scene's own; a
#     mesh found only there loads, and without it the error names the mesh.
mkdir -p "$TMP/assets/meshes" "$TMP/sc"
printf 'v -1 -1 0\nv 1 -1 0\nv 1 1 0\nf 1 2 3\n' > "$TMP/assets/meshes/tri.obj"
sed 's|</scene>|<shape type="obj"><string name="filename" value="meshes/tri.obj"/></shape></scene>|' "$TMP/ok.xml" > "$TMP/sc/a.xml"
"$SNELL" render "$TMP/sc/a.xml" -o "$TMP/a.exr" --spp 1 -q -a "$TMP/nowhere;$TMP/assets"; rc=$?
check "-a finds a mesh in the extra folder" "[ $rc -eq 0 ] && [ -s $TMP/a.exr ]"
out=$("$SNELL" render "$TMP/sc/a.xml" -o "$TMP/a2.exr" --spp 1 -q 2>&1); rc=$?
check "without -a the mesh is missing" "[ $rc -ne 0 ] && echo \"\$out\" | grep -q 'meshes/tri.obj'"

# 11. Issue 12: bad numbers on the command line exit 2 (a usage error, issue 27) with a message
#     that says what is expected (they exited 104/105 with a 300-digit bound, and --time nan was
#     accepted); a radiance of 1e300 gives an image without Inf (each sample saturated at the
#     film's exact range, 2^80, issue 27), counted in the stats, and so do an environment map of
#     FLT_MAX texels and one scaled by 1e300.
for args in "--spp 0" "--threads -1" "--threads 1000000" "--time nan" "--time -1"; do
  out=$("$SNELL" render builtin:droplet -o "$TMP/bad.exr" -q $args 2>&1); rc=$?
  check "$args exits 2 with a clear message" "[ $rc -eq 2 ] && echo \"\$out\" | grep -q 'range\\|expected a positive'"
done
cat > "$TMP/huge.xml" <<'XML'
<scene version="3.0.0"><integrator type="path"/>
<sensor type="perspective"><float name="fov" value="40"/><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
<emitter type="constant"><float name="radiance" value="1e300"/></emitter></scene>
XML
"$SNELL" render "$TMP/huge.xml" -o "$TMP/huge.exr" --spp 2 -q; rc=$?
check "radiance 1e300 renders" "[ $rc -eq 0 ]"
check "values beyond the film's range are counted" "grep -q '\"saturated\": [1-9]' $TMP/huge.json"
# An environment map whose texels are the largest RGBE value (1.7e38, about FLT_MAX), and the
# same map with scale 1e300: the images hold no Inf and the samples that were are counted.
{ printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n'; for i in $(seq 32); do printf '\377\377\377\377'; done; } > "$TMP/max.hdr"
for scale in 1 1e300; do
  sed "s|<emitter type=\"constant\"><float name=\"radiance\" value=\"1e300\"/></emitter>|<emitter type=\"envmap\"><string name=\"filename\" value=\"max.hdr\"/><float name=\"scale\" value=\"$scale\"/></emitter>|" "$TMP/huge.xml" > "$TMP/env_max.xml"
  "$SNELL" render "$TMP/env_max.xml" -o "$TMP/env_max.exr" --spp 2 -q; rc=$?
  out=$("$SNELL" diff "$TMP/env_max.exr" "$TMP/env_max.exr" 2>&1)
  check "envmap of FLT_MAX texels, scale $scale: renders, no Inf in the image" "[ $rc -eq 0 ] && echo \"\$out\" | grep -q '^image .* mean [0-9.e+]* (reference' && ! echo \"\$out\" | grep -qi 'inf (ref\|nan'"
done
check "envmap scale 1e300: the infinite samples are counted" "grep -q '\"inf\": 128' $TMP/env_max.json"

# 12. Issue 12: an <include> of a FIFO blocked forever (the file was opened before it was checked
#     to be a regular file); it is an error now, as is a scene file that is a folder.
mkfifo "$TMP/fifo.xml"
printf '<scene version="3.0.0"><include filename="fifo.xml"/></scene>\n' > "$TMP/inc_fifo.xml"
out=$(timeout 60 "$SNELL" render "$TMP/inc_fifo.xml" -o "$TMP/fifo.exr" -q 2>&1); rc=$?
check "an <include> of a FIFO is an error, not a hang" "[ $rc -eq 1 ] && echo \"\$out\" | grep -q 'inc_fifo.xml:1: <include>'"
out=$(timeout 60 "$SNELL" render "$TMP" -o "$TMP/dir.exr" -q 2>&1); rc=$?
check "a folder as the scene is an error" "[ $rc -eq 1 ]"


# 13. Issue 30: output names mean what was typed. -o DIR wrote DIR.exr, -o out.png wrote
#     out.png.exr, -o /dev/full wrote /dev/full.exr (exit 0), --stats X.exr -o X.exr replaced the
#     image with the JSON, a missing folder was created, --seed -1 became 2^64-1 and
#     --exposure nan was accepted.
mkdir -p "$TMP/outdir"
for o in "$TMP/outdir" "$TMP/noext" /dev/full "$TMP/x.jpg"; do
  out=$("$SNELL" render builtin:droplet --spp 1 -q -o "$o" 2>&1); rc=$?
  check "-o $o is refused with a clear message" "[ $rc -eq 1 ] && echo \"\$out\" | grep -q 'is a folder\|must end in .exr'"
done
check "nothing was written for the refused names" "[ ! -e \"$TMP/outdir.exr\" ] && [ ! -e \"$TMP/noext.exr\" ] && [ ! -e /dev/full.exr ]"
"$SNELL" render builtin:droplet --spp 1 -q -o "$TMP/only.png"; rc=$?
check "-o NAME.png writes the PNG and its stats alone" "[ $rc -eq 0 ] && [ -s \"$TMP/only.png\" ] && [ -s \"$TMP/only.json\" ] && [ ! -e \"$TMP/only.png.exr\" ] && [ ! -e \"$TMP/only.exr\" ]"
"$SNELL" render builtin:droplet --spp 1 -q -o "$TMP/both.exr"; rc=$?
check "-o NAME.exr writes the EXR and its PNG preview" "[ $rc -eq 0 ] && [ -s \"$TMP/both.exr\" ] && [ -s \"$TMP/both.png\" ] && [ -s \"$TMP/both.json\" ]"
cp "$TMP/both.exr" "$TMP/keep.exr"
for st in "$TMP/both.exr" "$TMP/../$(basename "$TMP")/both.png"; do
  out=$("$SNELL" render builtin:droplet --spp 1 -q -o "$TMP/both.exr" --stats "$st" 2>&1); rc=$?
  check "--stats $st naming an image is refused" "[ $rc -eq 1 ] && echo \"\$out\" | grep -q 'would replace it'"
done
check "the refused --stats left the image as it was" "cmp -s \"$TMP/both.exr\" \"$TMP/keep.exr\""
out=$("$SNELL" render builtin:droplet --spp 1 -q -o "$TMP/missing/dir/x.exr" 2>&1); rc=$?
check "a missing folder is an error" "[ $rc -eq 1 ] && echo \"\$out\" | grep -q 'does not exist (create it, or pass --mkdir)' && [ ! -e \"$TMP/missing\" ]"
"$SNELL" render builtin:droplet --spp 1 -q -o "$TMP/made/dir/x.exr" --mkdir; rc=$?
check "--mkdir creates it" "[ $rc -eq 0 ] && [ -s \"$TMP/made/dir/x.exr\" ]"
for args in "--seed -1" "--seed 18446744073709551616" "--seed 1e3" "--exposure nan" "--exposure inf" "--exposure 1e9"; do
  out=$("$SNELL" render builtin:droplet --spp 1 -q -o "$TMP/n.exr" $args 2>&1); rc=$?
  check "$args exits 2 with a clear message" "[ $rc -eq 2 ] && echo \"\$out\" | grep -q 'expected a seed\|expected an exposure'"
done
"$SNELL" render builtin:droplet --spp 1 -q -o "$TMP/s.exr" --seed 18446744073709551615; rc=$?
check "--seed 2^64-1 is a seed" "[ $rc -eq 0 ] && grep -q '18446744073709551615' \"$TMP/s.json\""


# 14. Issue 30: `snell compare --time 1e-300` ranked integrators that drew no sample.
out=$("$SNELL" compare builtin:droplet --integrators nee,mnee --time 1e-300 --reference-spp 2 --convergence-steps 0 -q -o "$TMP/cmp" 2>&1); rc=$?
check "compare shows integrators that drew no sample unranked" "[ $rc -eq 0 ] && echo \"\$out\" | grep -q '^-  *nee .*not ranked: drew no sample' && grep -q '\"order_by_psnr\": \[\]' \"$TMP/cmp/report.json\" && grep -q '\"rank\": null' \"$TMP/cmp/report.json\""

exit $fail
