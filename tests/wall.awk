# A floor slab (140 x 100 x 2 mm) and a thin wall (2 x 30 x 100 mm) standing on it, both
# closed boxes (an open floor would leave jade to guess which way its faces look), as OBJ in mm.
# The wall runs along z, so the shadow of its top edge is a straight line across the floor.
# awk -v dense=1: every face of both boxes gridded at about 2 mm (the floor's underside as
# dense as its top: a mesh whose two sides share the light map proxy's cells), not only the
# top faces; -v step=S: at about S mm instead (0.5: 283,840 triangles, past the 2^17 up to which
# jade measures the thickness with a ray a vertex).
function box(x0, x1, y0, y1, z0, z1, nx, nz,   i, j, k, x, y, z, b, X, Y, Z) {
    if (dense) {
        X = x1 - x0; Y = y1 - y0; Z = z1 - z0
        face(x0, y1, z0, 0, 0, Z, X, 0, 0); face(x0, y0, z0, X, 0, 0, 0, 0, Z)
        face(x0, y0, z0, 0, 0, Z, 0, Y, 0); face(x1, y0, z0, 0, Y, 0, 0, 0, Z)
        face(x0, y0, z0, 0, Y, 0, X, 0, 0); face(x0, y0, z1, X, 0, 0, 0, Y, 0)
        return
    }
    # the top face as a grid of nx x nz quads (per-vertex terms need vertices), the rest single quads
    b = nv
    for (j = 0; j <= nz; j++) for (i = 0; i <= nx; i++) { printf "v %g %g %g\n", x0 + (x1 - x0) * i / nx, y1, z0 + (z1 - z0) * j / nz; nv++ }
    for (j = 0; j < nz; j++) for (i = 0; i < nx; i++) {
        a = b + j * (nx + 1) + i + 1; c = a + nx + 1
        printf "f %d %d %d\nf %d %d %d\n", a, c, c + 1, a, c + 1, a + 1
    }
    # the other five faces from the 8 corners
    o = nv
    for (k = 0; k < 8; k++) { printf "v %g %g %g\n", (k % 2) ? x1 : x0, (int(k / 2) % 2) ? y1 : y0, (int(k / 4)) ? z1 : z0; nv++ }
    q("0 4 6 2"); q("1 3 7 5"); q("0 1 5 4"); q("0 2 3 1"); q("4 5 7 6")
}
function q(s,   t) { split(s, t, " "); printf "f %d %d %d\nf %d %d %d\n", o + t[1] + 1, o + t[2] + 1, o + t[3] + 1, o + t[1] + 1, o + t[3] + 1, o + t[4] + 1 }
# A face from corner o along u and v (u x v outward) in quads of about 2 mm.
function face(ox, oy, oz, ux, uy, uz, vx, vy, vz,   nu, nw, i, j, b, a, c) {
    nu = cells(ux, uy, uz); nw = cells(vx, vy, vz); b = nv
    for (j = 0; j <= nw; j++) for (i = 0; i <= nu; i++) {
        printf "v %g %g %g\n", ox + ux * i / nu + vx * j / nw, oy + uy * i / nu + vy * j / nw, oz + uz * i / nu + vz * j / nw; nv++
    }
    for (j = 0; j < nw; j++) for (i = 0; i < nu; i++) {
        a = b + j * (nu + 1) + i + 1; c = a + nu + 1
        printf "f %d %d %d\nf %d %d %d\n", a, a + 1, c + 1, a, c + 1, c
    }
}
function cells(x, y, z,   n) { n = int(sqrt(x * x + y * y + z * z) / (step ? step : 2) + 0.5); return n < 1 ? 1 : n }
BEGIN { nv = 0; box(-50, 90, -2, 0, -50, 50, 70, 50); box(-1, 1, 0, 30, -50, 50, 1, 50) }
