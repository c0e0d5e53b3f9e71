#!/bin/sh
# The program's behaviour on good and bad command lines: one-line errors,
# non-zero exits, no crash and no half-written output.
jade=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
mesh0=$(dirname "$0")/../assets/default.drc
expect() { # expect NAME WANT_RC GREP_PATTERN -- command...
    name=$1 want=$2 pat=$3
    shift 4
    "$@" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    lines=$(wc -l < "$tmp/err")
    if [ "$rc" -eq "$want" ] && { [ -z "$pat" ] || grep -q -- "$pat" "$tmp/out" "$tmp/err"; } &&
       { [ "$want" -eq 0 ] || [ "$lines" -eq 1 ]; }; then
        pass=$((pass + 1))
        [ "$want" -ne 0 ] && echo "ok   $name: $(cat "$tmp/err")"
    else
        fail=$((fail + 1))
        echo "FAIL $name: rc=$rc (want $want), stderr lines=$lines"
        cat "$tmp/out" "$tmp/err"
    fi
}
expect "no command" 2 "no command" -- "$jade"
expect "help" 0 "render" -- "$jade" --help
expect "render help" 0 "--material" -- "$jade" render --help
expect "bench help" 0 "--frames" -- "$jade" bench --help
expect "unknown command" 2 "unknown command 'paint'" -- "$jade" paint
expect "unknown flag" 2 "unknown option '--colour'" -- "$jade" render --colour red
expect "missing value" 2 "needs a value" -- "$jade" render --size
expect "bad size" 2 "expected WxH" -- "$jade" render --size 12xabc
expect "size that wraps round" 2 "got '4294967312x16'" -- "$jade" render --size 4294967312x16
expect "size with a sign" 2 "expected WxH" -- "$jade" render --size +64x64
expect "size with a tail" 2 "expected WxH" -- "$jade" render --size 64x64x2
# A light map that is not a power of two put every shadow in the wrong place.
expect "light map not a power of two" 1 "light map size 200 must be a power of two" -- "$jade" render --light-map 200 --diffusion-size 32 --out "$tmp/lm.png"
# A diffusion texel past 16 x 16 light-map texels: its loop read part of the square.
expect "diffusion texel over 16 light-map texels a side" 1 "diffusion texel gathers at most 16 x 16 light-map texels (diffusion size at least 64)" -- "$jade" render --light-map 1024 --diffusion-size 32 --out "$tmp/ds.png"
expect "option=value" 0 "wrote $tmp/eq.png (48x32" -- "$jade" render --size=48x32 --out="$tmp/eq.png" --mode=none
# --pixel-samples: drawn at N times the size, written at the size asked.
expect "pixel samples" 0 "wrote $tmp/ps.png (48x32 from 144x96, 3 x 3 samples a pixel" -- "$jade" render --size 48x32 --pixel-samples 3 --out "$tmp/ps.png" --mode none
expect "pixel samples, the picture's size" 0 "rmse" -- "$jade" metric "$tmp/ps.png" "$tmp/eq.png"
expect "pixel samples out of range" 2 "expected a whole number from 1 to 8, got '9'" -- "$jade" render --pixel-samples 9 --out "$tmp/ps9.png"
expect "pixel samples over the largest size" 2 "draws 4160x2080, over 4096 a side" -- "$jade" render --size 520x260 --pixel-samples 8 --out "$tmp/ps8.png"
expect "pixel samples with a sheet" 2 "not with --sheet" -- "$jade" render --pixel-samples 2 --sheet "$tmp/pss.png"
expect "flag=value" 2 "takes no value" -- "$jade" render --no-cull=1
expect "did you mean" 2 "did you mean --frames?" -- "$jade" render --frame 3
long=1.$(printf '0%.0s' $(seq 1 300))1
expect "a long triple is read whole" 0 "wrote" -- "$jade" render --size 32x32 --out "$tmp/eq.png" --sigma-s "$long,$long,$long"
expect "a long triple's end is checked" 2 "three numbers" -- "$jade" render --sigma-s "$long,$long,${long}x"
# The light a path tracer is given (tools/cycles-reference.sh): no ambient,
# no highlight; each changes the picture, in jade and in its reference.
expect "no ambient, no highlight" 0 "wrote" -- "$jade" render --size 32x32 --out "$tmp/amb0.png" --ambient 0 --specular 0
expect "the default ambient" 0 "wrote" -- "$jade" render --size 32x32 --out "$tmp/amb1.png"
if cmp -s "$tmp/amb0.png" "$tmp/amb1.png"; then fail=$((fail + 1)); echo "FAIL --ambient 0 --specular 0 left the picture as it was"; else pass=$((pass + 1)); fi
expect "reference without ambient" 0 "wrote" -- "$jade" reference --size 24x24 --samples 20000 --quiet --out "$tmp/ramb0.png" --ambient 0 --specular 0
expect "reference with ambient" 0 "wrote" -- "$jade" reference --size 24x24 --samples 20000 --quiet --out "$tmp/ramb1.png"
# Light between parts, on few samples: its check is tests/test_reference.c's
# (7), which the sanitizer build leaves out for its time; this is the code
# under the sanitizers.
expect "reference with light between parts" 0 "light between parts [0-9]* ms (1 bounce)" -- "$jade" reference --size 24x24 --samples 3000 --bounces 1 --out "$tmp/rbounce.png"
# The half-space's exact albedo is known for an index-matched boundary only.
if cmp -s "$tmp/ramb0.png" "$tmp/ramb1.png"; then fail=$((fail + 1)); echo "FAIL jade reference --ambient 0 left the picture as it was"; else pass=$((pass + 1)); fi
expect "negative ambient" 2 "--ambient: expected a number from 0 to 100" -- "$jade" render --ambient -1
expect "a triple with four" 2 "three numbers" -- "$jade" render --sigma-s 1,2,3,4
expect "a triple with an empty part" 2 "three numbers" -- "$jade" render --sigma-s 1,,3
longpath=$(printf 'a/%.0s' $(seq 1 2100))
expect "path too long" 2 "longer than the system allows" -- "$jade" render --mesh "$longpath"
expect "metric path too long" 2 "longer than the system allows" -- "$jade" metric "$longpath" x.png
expect "size out of range" 2 "expected WxH" -- "$jade" render --size 99999x2
expect "bad mode" 2 "none, single, dual or full" -- "$jade" render --mode triple
expect "bad material" 2 "unknown material 'jelly'" -- "$jade" render --material jelly
expect "bad number" 2 "expected a number" -- "$jade" render --eta 1.3x
expect "nan number" 2 "expected a number" -- "$jade" render --eta nan
expect "bad triple" 2 "three numbers" -- "$jade" render --sigma-a 1,2
expect "cube size 32" 0 "wrote" -- "$jade" render --cube-size 32 --mode dual --size 32x32 --out "$tmp/c32.png"
expect "cube size 32, vc4" 0 "wrote" -- "$jade" render --cube-size 32 --mode dual --size 32x32 --profile vc4 --out "$tmp/c32.png"
expect "bad cube size" 2 "multiple of 8" -- "$jade" render --cube-size 60
expect "missing mesh" 1 "cannot open" -- "$jade" render --mesh "$tmp/nope.drc" --out "$tmp/x.png"
# A decode stopped at its deadline says which option gives it more time.
expect "decode past its deadline" 1 "decoding took longer than 1 ms; refused (--decode-timeout-ms N gives it N ms)" -- \
    "$jade" render --mesh "$mesh0" --decode-timeout-ms 1 --out "$tmp/x.png"
printf 'hello' > "$tmp/hello.drc"
if command -v draco_encoder >/dev/null; then
    # A tetrahedron whose first texture coordinate is NaN (unquantised, so it survives encoding).
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt nan 0\nvt 0 1\nvt 1 1\nvt 1 0\nf 1/1 3/2 2/3\nf 1/1 2/3 4/4\nf 1/1 4/4 3/2\nf 2/3 3/2 4/4\n' > "$tmp/nan.obj"
    draco_encoder -i "$tmp/nan.obj" -o "$tmp/nan.drc" -cl 0 -qp 0 -qt 0 >/dev/null
    # The renderer drops texture coordinates in the decoder: nothing to refuse. A conversion keeps
    # them, so it checks them.
    expect "NaN texture coordinate, rendered" 0 "wrote" -- "$jade" render --mesh "$tmp/nan.drc" --size 32x32 --out "$tmp/nan.png"
    expect "NaN texture coordinate, converted" 1 "non-finite texture coordinate" -- "$jade" convert "$tmp/nan.drc" "$tmp/nan2.drc"
else
    echo "skip NaN attribute: no draco_encoder"
fi
expect "not a mesh" 1 "not a mesh jade reads" -- "$jade" render --mesh "$tmp/hello.drc" --out "$tmp/x.png"
expect "unwritable output" 1 "cannot write there" -- "$jade" render --size 64x64 --out "$tmp/no/such/dir/x.png"
expect "--out .jpg" 0 "wrote $tmp/pic.jpg" -- "$jade" render --size 32x32 --out "$tmp/pic.jpg"
check_jpeg() { [ "$(head -c 3 "$tmp/pic.jpg" | od -An -tx1 | tr -d ' ')" = "ffd8ff" ]; }
if check_jpeg; then pass=$((pass + 1)); echo "ok   a .jpg name gets a JPEG"; else fail=$((fail + 1)); echo "FAIL a .jpg name did not get a JPEG"; fi
expect "--out .bmp" 1 "jade writes pictures as PNG or JPEG" -- "$jade" render --size 32x32 --out "$tmp/pic.bmp"
expect "1920x1080 with the default budget" 0 "wrote $tmp/hd.png (1920x1080" -- "$jade" render --size 1920x1080 --out "$tmp/hd.png"
rm -f "$tmp/hd.png"
expect "tiny budget" 1 "memory budget exhausted" -- "$jade" render --budget-mb 1 --out "$tmp/x.png"
left=$(ls "$tmp" | grep -c '\.tmp\.' || true)
if [ ! -e "$tmp/x.png" ] && [ "$left" -eq 0 ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: a failed run left output behind"; ls "$tmp"; fi
expect "render default" 0 "wrote $tmp/ok.png" -- "$jade" render --size 96x64 --out "$tmp/ok.png"
if [ -s "$tmp/ok.png" ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: no PNG written"; fi
expect "sheet" 0 "none | single | dual | full" -- "$jade" render --size 64x64 --sheet "$tmp/sheet.png"
expect "info" 0 "fragment highp" -- "$jade" info
expect "metric same" 0 '"ssim": 1.00000' -- "$jade" metric "$tmp/ok.png" "$tmp/ok.png"
expect "metric one picture" 2 "needs two pictures" -- "$jade" metric "$tmp/ok.png"
expect "metric unreadable" 1 "not a PNG" -- "$jade" metric "$tmp/hello.drc" "$tmp/ok.png"
expect "metric size mismatch" 1 "is 96x64 but" -- "$jade" metric "$tmp/ok.png" "$tmp/sheet.png"
expect "metric --mask=" 2 "needs two pictures" -- "$jade" metric --mask="$tmp/ok.png" "$tmp/ok.png"
# Nothing to compare is an error, not a perfect score.
# A black 4x4 PNG and a black 96x64 grey PNG.
printf '\211\120\116\107\015\012\032\012\000\000\000\015\111\110\104\122\000\000\000\004\000\000\000\004\010\002\000\000\000\046\223\011\051\000\000\000\014\111\104\101\124\170\332\143\140\040\035\000\000\000\064\000\001\110\243\175\157\000\000\000\000\111\105\116\104\256\102\140\202' > "$tmp/black.png"
expect "metric of two flat pictures" 1 "no pixel differs" -- "$jade" metric "$tmp/black.png" "$tmp/black.png"
printf '\211\120\116\107\015\012\032\012\000\000\000\015\111\110\104\122\000\000\000\140\000\000\000\100\010\000\000\000\000\300\137\055\322\000\000\000\035\111\104\101\124\170\332\355\301\061\001\000\000\000\302\240\365\117\355\155\007\240\000\000\000\000\000\000\336\000\030\100\000\001\231\226\363\363\000\000\000\000\111\105\116\104\256\102\140\202' > "$tmp/empty.png"
expect "metric with an empty mask" 1 "the mask has no nonzero pixel" -- "$jade" metric "$tmp/ok.png" "$tmp/ok.png" --mask "$tmp/empty.png"
# stb_image's PNM reader overflows the heap on this 15-byte file (found by
# tests/fuzz/fuzz_image): jade reads PNG and PFM only.
printf 'P62 2\011622 2 2\033\023' > "$tmp/overflow.ppm"
expect "metric refuses other formats" 1 "not a PNG" -- "$jade" metric "$tmp/overflow.ppm" "$tmp/overflow.ppm"
# JSON out stays JSON whatever the file is called: a quote, a newline, a
# control character and a byte that is not UTF-8.
odd="$tmp/$(printf 'q\"u\\o\nte\001\377.png')"
cp "$tmp/ok.png" "$odd"
expect "metric output with an odd name" 0 '"ssim"' -- "$jade" metric "$odd" "$tmp/ok.png"
json_ok() { if command -v python3 >/dev/null; then python3 -c "$@"; else echo "skip JSON parse: no python3"; fi; }
if json_ok 'import json,sys; d=json.load(open(sys.argv[1])); want=sys.argv[2].encode("utf-8","surrogateescape").decode("utf-8","replace"); assert d["a"] == want, (d["a"], want)' "$tmp/out" "$odd"; then
    pass=$((pass + 1)); echo "ok   metric's JSON parses and keeps the name"
else fail=$((fail + 1)); echo "FAIL metric's JSON with an odd name"; cat "$tmp/out"; fi
cp "$mesh0" "$odd.drc"
expect "bench output with an odd name" 0 '"modes"' -- "$jade" bench --size 32x32 --frames 2 --mode none --mesh "$odd.drc"
if json_ok 'import json,sys; d=json.load(open(sys.argv[1])); assert d["mesh"].endswith(".png.drc")' "$tmp/out"; then
    pass=$((pass + 1)); echo "ok   bench's JSON parses"
else fail=$((fail + 1)); echo "FAIL bench's JSON with an odd name"; cat "$tmp/out"; fi
# The reference: small, so the suite stays fast; the same scene options.
expect "reference help" 0 "--samples" -- "$jade" reference --help
expect "reference bad flag" 2 "unknown option '--mode'" -- "$jade" reference --mode dual
expect "reference bad samples" 2 "expected a whole number" -- "$jade" reference --samples 10
expect "reference missing mesh" 1 "cannot open" -- "$jade" reference --mesh "$tmp/nope.drc" --out "$tmp/r.png"
expect "reference not a mesh" 1 "not a mesh jade reads" -- "$jade" reference --mesh "$tmp/hello.drc" --out "$tmp/r.png"
expect "reference unwritable" 1 "cannot write there" -- "$jade" reference --size 32x32 --out "$tmp/no/dir/r.png" --quiet
if [ ! -e "$tmp/r.png" ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: a failed reference left r.png"; fi
expect "reference" 0 "wrote $tmp/ref.png, $tmp/ref.pfm, $tmp/mask.png" -- \
    "$jade" reference --size 96x64 --out "$tmp/ref.png" --pfm "$tmp/ref.pfm" --mask "$tmp/mask.png" --samples 20000
if grep -q "reference" "$tmp/err" && [ -s "$tmp/ref.pfm" ]; then pass=$((pass + 1)); echo "ok   reference progress: $(tail -n 1 "$tmp/err")"
else fail=$((fail + 1)); echo "FAIL: no progress on stderr or no PFM"; fi
expect "metric against the reference" 0 '"pixels": [1-9]' -- "$jade" metric "$tmp/ok.png" "$tmp/ref.png" --mask "$tmp/mask.png"
expect "metric against the PFM" 0 '"ssim"' -- "$jade" metric "$tmp/ok.png" "$tmp/ref.pfm" --mask "$tmp/mask.png"
expect "sheet with reference" 0 "reference | none | single | dual | full" -- \
    "$jade" render --size 96x64 --sheet "$tmp/sheet4.png" --sheet-reference "$tmp/ref.png"
expect "sheet reference wrong size" 1 "not the size" -- \
    "$jade" render --size 64x64 --sheet "$tmp/sheet5.png" --sheet-reference "$tmp/ref.png"
t0=$(date +%s%N)
expect "kiosk without drm" 1 "" -- "$jade" kiosk --drm-device "$tmp/no-card0"
t1=$(date +%s%N)
if [ $(( (t1 - t0) / 1000000 )) -lt 1000 ]; then pass=$((pass + 1)); echo "ok   kiosk refused in $(( (t1 - t0) / 1000000 )) ms"; else fail=$((fail + 1)); echo "FAIL: kiosk took $(( (t1 - t0) / 1000000 )) ms to refuse"; fi
expect "kiosk bad mode" 2 "" -- "$jade" kiosk --rotate 45
expect "kiosk statistics" 0 "missed vblanks" -- "$jade" kiosk --platform headless --frames 20 --size 96x96
if [ ! -e /dev/dri ]; then
    expect "kiosk no device" 1 "no DRM/KMS display device" -- "$jade" kiosk
fi
expect "view bad screenshot" 2 "needs --frames" -- "$jade" view --screenshot "$tmp/v.png"
expect "info profile" 0 "per fragment (no vertex texture units)" -- "$jade" info --profile mali400
expect "bad profile" 2 "unknown profile 'ps2'" -- "$jade" info --profile ps2
expect "render bad profile" 2 "unknown profile 'ps2'" -- "$jade" render --profile ps2

# Outputs never destroy anything; inputs that are not regular files (a FIFO
# would block) or that declare huge pictures are refused at once.
check() { if eval "$2"; then pass=$((pass + 1)); echo "ok   $1"; else fail=$((fail + 1)); echo "FAIL $1"; fi; }
check "no picture from a refused --pixel-samples" '[ ! -e "$tmp/ps9.png" ] && [ ! -e "$tmp/ps8.png" ] && [ ! -e "$tmp/pss.png" ]'
mesh=$(dirname "$0")/../assets/default.drc
cp "$mesh" "$tmp/m.drc"
expect "out onto the mesh" 1 "is one of this run's inputs" -- "$jade" render --mesh "$tmp/m.drc" --size 32x32 --out "$tmp/m.drc"
check "the mesh is intact" 'cmp -s "$mesh" "$tmp/m.drc"'
expect "out onto a device" 1 "not a regular file" -- "$jade" render --size 32x32 --out /dev/null
check "/dev/null is still a device" '[ -c /dev/null ]'
echo keep > "$tmp/target"
ln -s "$tmp/target" "$tmp/link.png"
expect "out through a symlink" 1 "symbolic link" -- "$jade" render --size 32x32 --out "$tmp/link.png"
check "the symlink's target is intact" '[ "$(cat "$tmp/target")" = keep ]'
expect "sheet leaves --out alone" 0 "wrote" -- "$jade" render --size 32x32 --out /dev/null --sheet "$tmp/s2.png"
check "/dev/null is still a device after the sheet" '[ -c /dev/null ]'
expect "reference out onto a device" 1 "not a regular file" -- "$jade" reference --size 16x16 --quiet --out /dev/null
# A sequence (--light-step, a %d in --out): every frame under its number,
# each the picture one run would draw at its light (tests/flicker.sh relies
# on that); a name refused before the first frame writes none.
expect "a sequence" 0 "wrote $tmp/seq00.png to $tmp/seq02.png (3 frames" -- "$jade" render --size 32x32 --light-azimuth 140 --light-step 10 --frames 3 --out "$tmp/seq%02d.png"
expect "the sequence's last light in one run" 0 "wrote" -- "$jade" render --size 32x32 --light-azimuth 160 --out "$tmp/seq160.png"
check "frame 2 is the picture at 160 degrees" 'cmp -s "$tmp/seq02.png" "$tmp/seq160.png"'
check "the light turned between frames" '! cmp -s "$tmp/seq00.png" "$tmp/seq01.png"'
# The reference's sequence: its samples placed once (jd_ref_relight), each
# frame the picture of a run of its own, with light between parts as well.
expect "a reference sequence" 0 "wrote $tmp/rs0.png to $tmp/rs1.png" -- "$jade" reference --size 24x24 --samples 3000 --bounces 1 --light-azimuth 100 --light-step 30 --frames 2 --quiet --out "$tmp/rs%d.png"
expect "its last light in one run" 0 "wrote" -- "$jade" reference --size 24x24 --samples 3000 --bounces 1 --light-azimuth 130 --quiet --out "$tmp/rs130.png"
check "the reference's frame 1 is the picture at 130 degrees" 'cmp -s "$tmp/rs1.png" "$tmp/rs130.png"'
expect "the volume's one light" 2 "--volume draws one frame" -- "$jade" reference --volume --frames 2 --size 16x16
expect "single scattering needs eta 1" 2 "needs --eta 1, not 1.5" -- "$jade" reference --single-scatter --material marble --size 16x16
expect "a % that is not a number" 1 "numbers the frames, once, as %d or %0Nd" -- "$jade" render --size 32x32 --out "$tmp/x%s.png"
expect "two numbers" 1 "numbers the frames, once" -- "$jade" render --size 32x32 --frames 2 --out "$tmp/x%d-%d.png"
ln -s "$tmp/target" "$tmp/lk1.png"
expect "a sequence's frame through a symlink" 1 "lk1.png: is a symbolic link" -- "$jade" render --size 32x32 --frames 3 --out "$tmp/lk%d.png"
check "nothing of it written" '[ ! -e "$tmp/lk0.png" ] && [ "$(cat "$tmp/target")" = keep ]'
mkfifo "$tmp/fifo"
expect "mesh is a FIFO" 1 "not a regular file" -- timeout 10 "$jade" render --mesh "$tmp/fifo" --out "$tmp/x.png"
expect "metric input is a FIFO" 1 "not a regular file" -- timeout 10 "$jade" metric "$tmp/fifo" "$tmp/fifo"
mkfifo "$tmp/fifo.pfm"
expect "metric PFM is a FIFO" 1 "not a regular file" -- timeout 10 "$jade" metric "$tmp/fifo.pfm" "$tmp/fifo.pfm"
"$jade" render --size 32x32 --out "$tmp/a.png" >/dev/null 2>&1
expect "mask is a FIFO" 1 "not a regular file" -- timeout 10 "$jade" metric "$tmp/a.png" "$tmp/a.png" --mask "$tmp/fifo"
expect "sheet reference is a FIFO" 1 "not a regular file" -- \
    timeout 10 "$jade" render --size 32x32 --sheet "$tmp/s.png" --sheet-reference "$tmp/fifo"
# A 74-byte PNG whose header declares 100000 x 100000 pixels (40 GB decoded).
printf '\211\120\116\107\015\012\032\012\000\000\000\015\111\110\104\122\000\001\206\240\000\001\206\240\010\006\000\000\000\250\122\013\310\000\000\000\021\111\104\101\124\170\332\143\140\030\005\243\140\024\014\167\000\000\003\350\000\001\316\111\114\130\000\000\000\000\111\105\116\104\256\102\140\202' > "$tmp/bomb.png"
expect "picture bomb" 1 "over jade's limit of 16777216 pixels (4096 a side)" -- timeout 10 "$jade" metric "$tmp/bomb.png" "$tmp/a.png"
# A full disk: a 64 KiB tmpfs (root only); the previous picture survives.
mkdir -p "$tmp/small"
if [ "$(id -u)" -eq 0 ] && mount -t tmpfs -o size=64k tmpfs "$tmp/small" 2>/dev/null; then
    "$jade" render --size 32x32 --out "$tmp/small/pic.png" >/dev/null 2>&1
    cp "$tmp/small/pic.png" "$tmp/prev.png"
    expect "disk full" 1 "No space left on device" -- "$jade" render --size 512x512 --out "$tmp/small/pic.png"
    check "the previous picture survives a full disk" 'cmp -s "$tmp/small/pic.png" "$tmp/prev.png"'
    check "no temporary file is left" '[ "$(ls "$tmp/small" | wc -l)" -eq 1 ]'
    umount "$tmp/small"
else
    echo "skip full disk: needs root and a tmpfs mount"
fi
echo "cli: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
