/* Every mesh in ../shared/testdata/draco decodes through jade and matches
 * Debian's draco_decoder at every face corner; every point cloud is refused. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mesh_load.h"

static float obj_v[1 << 20][3];
static unsigned obj_f[1 << 20][3];
static int obj_polygons; /* faces with more than 3 corners (preserved polygons) */
static long obj_triangles;

static int read_obj(const char *path, int *nv, int *nf)
{
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    char line[512];
    *nv = *nf = 0;
    obj_polygons = 0;
    obj_triangles = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ' && *nv < (1 << 20)) {
            sscanf(line + 2, "%f %f %f", &obj_v[*nv][0], &obj_v[*nv][1], &obj_v[*nv][2]);
            (*nv)++;
        } else if (line[0] == 'f' && line[1] == ' ' && *nf < (1 << 20)) {
            char *p = line + 2;
            int k = 0;
            for (; *p && *p != '\n'; k++) {
                unsigned v = (unsigned)strtoul(p, &p, 10) - 1;
                if (k < 3) obj_f[*nf][k] = v;
                while (*p && *p != ' ' && *p != '\n') p++;
                while (*p == ' ') p++;
            }
            if (k > 3) obj_polygons++;
            obj_triangles += k - 2;
            (*nf)++;
        }
    }
    fclose(f);
    return 1;
}

static int is_point_cloud(const char *path)
{
    unsigned char h[8] = {0};
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    size_t n = fread(h, 1, 8, f);
    fclose(f);
    return n == 8 && h[7] == 0;
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "../shared/testdata/draco";
    const char *tmp = argc > 2 ? argv[2] : "/tmp";
    DIR *d = opendir(dir);
    if (!d) {
        printf("SKIP: %s is absent (the shared test data sits beside the checkout as ../shared)\n", dir);
        return 77;
    }
    static unsigned char mem[64 << 20];
    struct dirent *e;
    int files = 0;
    while ((e = readdir(d))) {
        size_t len = strlen(e->d_name);
        if (len < 5 || strcmp(e->d_name + len - 4, ".drc")) continue;
        char path[1024], obj[1024], cmd[3072];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        snprintf(obj, sizeof obj, "%s/ref_%s.obj", tmp, e->d_name);
        jd_arena a;
        jd_arena_init(&a, mem, sizeof mem);
        jd_mesh m;
        jd_load_stats st;
        jd_error err = {0};
        /* The file's face order, to compare corner by corner with draco_decoder. */
        jd_load_desc ld = {.path = path, .allow_32bit_indices = 1, .timeout_ms = 5000, .keep_face_order = 1};
        jd_result r = jd_mesh_load_draco(&ld, &a, &m, &st, &err);
        files++;
        if (is_point_cloud(path)) {
            CHECK(r == JD_ERR_FORMAT && strstr(err.msg, "point cloud") && strstr(err.msg, e->d_name),
                  "%s refused as a point cloud: %s", e->d_name, err.msg);
            printf("%-42s refused: %s\n", e->d_name, err.msg);
            continue;
        }
        CHECK(r == JD_OK, "%s decodes: %s", e->d_name, err.msg);
        if (r) continue;
        snprintf(cmd, sizeof cmd, "draco_decoder -i '%s' -o '%s' >/dev/null 2>&1", path, obj);
        int nv = 0, nf = 0;
        CHECK(system(cmd) == 0 && read_obj(obj, &nv, &nf), "draco_decoder reads %s", e->d_name);
        remove(obj);
        float ext = fmaxf(m.bmax.x - m.bmin.x, fmaxf(m.bmax.y - m.bmin.y, m.bmax.z - m.bmin.z));
        double worst = 0;
        int bad_index = 0;
        if (obj_polygons) {
            /* The file preserves polygons, which draco_decoder writes back as
             * n-gons: compare triangle counts and that every corner of ours
             * is one of its vertices. */
            CHECK(obj_triangles == (long)(m.num_indices / 3), "%s: %u triangles, draco_decoder's polygons make %ld",
                  e->d_name, m.num_indices / 3, obj_triangles);
            for (uint32_t i = 0; i < m.num_indices; i++) {
                const float *p = m.positions + 3 * jd_mesh_index(&m, i);
                double best = 1e30;
                for (int v = 0; v < nv; v++) {
                    double dd = fmax(fabs(p[0] - obj_v[v][0]), fmax(fabs(p[1] - obj_v[v][1]), fabs(p[2] - obj_v[v][2])));
                    if (dd < best) best = dd;
                }
                if (best > worst) worst = best;
            }
            nf = 0;
        } else {
            CHECK((unsigned)nf == m.num_indices / 3, "%s: %u faces, draco_decoder %d", e->d_name, m.num_indices / 3, nf);
            if ((unsigned)nf != m.num_indices / 3) continue;
        }
        for (int f = 0; f < nf; f++)
            for (int k = 0; k < 3; k++) {
                uint32_t ours = jd_mesh_index(&m, (uint32_t)(3 * f + k));
                unsigned ref = obj_f[f][k];
                if (ref >= (unsigned)nv) { bad_index = 1; continue; }
                for (int c = 0; c < 3; c++) {
                    double dd = fabs(m.positions[3 * ours + c] - obj_v[ref][c]);
                    if (dd > worst) worst = dd;
                }
            }
        /* draco_decoder prints 6 decimals; positions are otherwise identical. */
        double tol = 2e-6 * (ext > 1 ? ext : 1) + 1e-6;
        CHECK(!bad_index && worst <= tol, "%s: worst corner difference %.3g (tolerance %.3g)", e->d_name, worst, tol);
        printf("%-42s %6u faces %6u vertices  decode %6.2f ms  max corner diff %.2g%s%s\n", e->d_name, m.num_indices / 3,
               m.num_vertices, st.decode_ms, worst, m.normals_computed ? "  (normals computed)" : "",
               obj_polygons ? "  (polygons)" : "");
    }
    closedir(d);
    CHECK(files >= 10, "found the Draco test files (%d)", files);
    return jd_check_summary("draco reference");
}
