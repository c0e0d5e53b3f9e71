#!/bin/sh
# textured-mesh.sh IN.obj OUT.obj: a plain OBJ (v and f lines, as the
# Stanford bunny in ../shared is stored) given texture coordinates by a
# cylindrical projection about its vertical axis (twice round the picture)
# and jade's veined test texture (assets/textured/pebble.png) through an
# MTL beside OUT. For the quality table's and the tests' textured cases:
# made at test time, never committed (the mesh is not jade's).
set -eu
in=$1 out=$2
root=$(cd "$(dirname "$0")/.." && pwd)
dir=$(dirname "$out")
mkdir -p "$dir"
cp "$root/assets/textured/pebble.png" "$dir/veined.png"
printf 'newmtl veined\nmap_Kd veined.png\n' > "$dir/veined.mtl"
awk -v mtl=veined.mtl '
    /^v / { n++; x[n] = $2; y[n] = $3; z[n] = $4; if (n == 1 || $3 < lo) lo = $3; if (n == 1 || $3 > hi) hi = $3 }
    /^f / { nf++; f[nf] = $0 }
    END {
        print "mtllib " mtl
        cx = 0; cz = 0
        for (i = 1; i <= n; i++) { cx += x[i]; cz += z[i] }
        cx /= n; cz /= n
        for (i = 1; i <= n; i++) printf "v %s %s %s\n", x[i], y[i], z[i]
        for (i = 1; i <= n; i++)
            printf "vt %.6f %.6f\n", 2 * (atan2(z[i] - cz, x[i] - cx) / 6.2831853 + 0.5), (y[i] - lo) / (hi - lo)
        print "usemtl veined"
        for (k = 1; k <= nf; k++) {
            split(f[k], a, " ")
            line = "f"
            for (j = 2; j <= 4; j++) { split(a[j], b, "/"); line = line " " b[1] "/" b[1] }
            print line
        }
    }' "$in" > "$out"
