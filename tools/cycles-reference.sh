#!/bin/sh
# cycles-reference.sh [jade reference options] --out PREFIX [--samples N] [--bounces N] [--seed N]
#                     [--boundary matched|walk]
#
# The scene of a `jade reference` command line path-traced by Blender's Cycles
# (Debian's `blender`, headless, on the CPU): ground truth that jade did not
# write, for the quality table. A tool that makes reference pictures; never a
# dependency of jade (tools/cycles_scene.py has the scene and its reasons).
#
# The object is a homogeneous medium with the material's sigma_s' and
# sigma_a (isotropic scattering). --boundary matched (the default): no
# surface, index-matched; --boundary walk: Cycles' random-walk subsurface
# scattering given the colour and radius that its own mapping turns back into
# those sigma values, behind a diffuse boundary (cosine entry and exit, no
# Fresnel). Neither reflects or refracts as a smooth dielectric would (which a
# path tracer cannot sample under a directional light: docs/quality.md), so
# jade's options must say --eta 1 --ambient 0 (no light but the directional
# one) and the picture is compared with jade's at the same options;
# --specular is moot (neither boundary has a highlight). Meshes: OBJ, PLY or
# STL.
# Writes PREFIX.png (jade's tone curve), PREFIX.pfm (linear) and
# PREFIX.mask.png, and prints the Blender command it ran. --bounces: at most
# 1024 [1024], which Blender will not exceed (it clamps; the scene refuses).
#
#   tools/cycles-reference.sh --mesh bunny.obj --size 128x128 --material skin1 \
#       --eta 1 --ambient 0 --light-azimuth -30 --light-elevation 40 --out skin1_front
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
jade=${JADE:-$root/build/jade}
command -v blender >/dev/null 2>&1 || { echo "cycles-reference: needs Blender (apt-get install blender)" >&2; exit 1; }
[ -x "$jade" ] || { echo "cycles-reference: $jade is not built (it names the materials)" >&2; exit 1; }

material=marble sigma_s="" sigma_a="" eta="" ambient="" keys="" out=""
die() { echo "cycles-reference: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    [ $# -ge 2 ] || die "$1 needs a value"
    case $1 in
        --mesh) keys="$keys mesh=$2" ;;
        --size) keys="$keys size=$2" ;;
        --material) material=$2 ;;
        --sigma-s) sigma_s=$2 ;;
        --sigma-a) sigma_a=$2 ;;
        --eta) eta=$2 ;;
        --ambient) ambient=$2 ;;
        --specular) ;;
        --density) keys="$keys density=$2" ;;
        --mm-per-unit) keys="$keys mm_per_unit=$2" ;;
        --yaw | --cam-azimuth) keys="$keys cam_az=$2" ;;
        --pitch | --cam-elevation) keys="$keys cam_el=$2" ;;
        --fit) keys="$keys fit=$2" ;;
        --distance | --cam-distance) keys="$keys cam_distance=$2" ;;
        --fov) keys="$keys fov=$2" ;;
        --light-azimuth) keys="$keys light_az=$2" ;;
        --light-elevation) keys="$keys light_el=$2" ;;
        --light-intensity) keys="$keys light_intensity=$2" ;;
        --exposure) keys="$keys exposure=$2" ;;
        --samples) keys="$keys samples=$2" ;;
        --bounces) keys="$keys bounces=$2" ;;
        --seed) keys="$keys seed=$2" ;;
        --boundary) keys="$keys boundary=$2" ;;
        --out) out=$2 ;;
        *) die "$1: not an option this tool passes to Cycles" ;;
    esac
    shift 2
done
[ -n "$out" ] || die "--out PREFIX is required"
case " $keys" in *" mesh="*) ;; *) die "--mesh FILE (OBJ, PLY or STL) is required" ;; esac
case " $keys" in *" size="*) ;; *) keys="$keys size=512x512" ;; esac
[ "$eta" = 1 ] || [ "$eta" = 1.0 ] || die "neither boundary refracts or reflects: pass --eta 1 (and to jade)"
[ "$ambient" = 0 ] || [ "$ambient" = 0.0 ] || die "the light is the directional one only: pass --ambient 0 (and to jade)"
# The named material's coefficients, as jade has them; explicit ones win.
row=$("$jade" info --materials | awk -v m="$material" '$1 == m { print $2 "," $3 "," $4 " " $5 "," $6 "," $7 }')
if [ -z "$row" ] && { [ -z "$sigma_s" ] || [ -z "$sigma_a" ]; }; then die "$material: not a material jade knows (jade info --materials)"; fi
[ -n "$sigma_s" ] || sigma_s=${row% *}
[ -n "$sigma_a" ] || sigma_a=${row#* }
mkdir -p "$(dirname "$out")"
# shellcheck disable=SC2086
set -- blender -b --factory-startup --python "$root/tools/cycles_scene.py" -- $keys sigma_s="$sigma_s" sigma_a="$sigma_a" out="$out"
echo "$*"
"$@" > "$out.log" 2>&1 || { tail -20 "$out.log" >&2; die "Blender failed (log: $out.log)"; }
grep "^cycles_scene:" "$out.log"
