#include "options.h"

#include "board.h"
#include "profile.h"

#include <errno.h>
#include <unistd.h>
#include <sys/stat.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum { T_STR, T_PATH, T_INT, T_FLOAT, T_FLOAT3, T_SIZE, T_FLAG, T_MODE, T_PRECISION, T_ANTIALIAS, T_PROBE, T_KMS, T_LEVELS } opt_type;

typedef struct opt {
    const char *name;
    opt_type type;
    size_t offset;
    double lo, hi;
    int commands;
    const char *help;
} opt;

#define OFF(f) offsetof(jd_options, f)
/* R and B also cover the interactive commands where an option makes sense
 * there: the scene, material and device options. */
#define R (JD_OPT_RENDER | JD_OPT_VIEW | JD_OPT_KIOSK)
#define S (R | B | JD_OPT_REFERENCE) /* the scene: what the reference shares */
#define B JD_OPT_BENCH
#define RO JD_OPT_RENDER
#define V JD_OPT_VIEW
#define K JD_OPT_KIOSK
static const opt table[] = {
    {"--mesh", T_PATH, OFF(mesh), 0, 0, S, "FILE       Draco, glTF/GLB, OBJ, PLY or STL mesh, told apart by content [the default asset]"},
    {"--out", T_PATH, OFF(out), 0, 0, RO | JD_OPT_REFERENCE,
     "FILE.png   output image, PNG, or JPEG when named .jpg [jade.png]; %d or %0Nd numbers the frames (from 0)"},
    {"--sheet", T_PATH, OFF(sheet), 0, 0, RO, "FILE.png   none | single | dual | full side by side, labelled"},
    {"--sheet-reference", T_PATH, OFF(sheet_ref), 0, 0, RO, "FILE.png   with --sheet: a reference picture as the first panel"},
    {"--pfm", T_PATH, OFF(pfm), 0, 0, JD_OPT_REFERENCE, "FILE.pfm   also write the linear picture (before the tone curve)"},
    {"--mask", T_PATH, OFF(mask_out), 0, 0, JD_OPT_REFERENCE, "FILE.png   also write the object's pixels (255) for jade metric --mask"},
    {"--samples", T_INT, OFF(samples), 100, 4000000, JD_OPT_REFERENCE, "N          irradiance samples [one per (0.3 mm)^2, 20,000 to 400,000]"},
    {"--error", T_FLOAT, OFF(ref_error), 0.001, 10, JD_OPT_REFERENCE, "X          octree error bound: node area / distance^2 [0.01]"},
    {"--window-mm", T_FLOAT, OFF(window_mm), 0.001, 1000, JD_OPT_REFERENCE, "X          near-field window, integrated exactly [2.5 mm or 3 sample spacings]"},
    {"--pixel-samples", T_INT, OFF(pixel_samples), 1, 8, JD_OPT_REFERENCE | RO,
     "N          N x N samples a pixel, averaged in linear light (reference: rays; render: drawn N times the size, for a still's edges) [1]"},
    {"--bounces", T_INT, OFF(bounces), 0, 4, JD_OPT_REFERENCE, "N          rounds of light falling from one part of the object on another (inter-reflection), 8 rays a sample each [0]"},
    {"--single-scatter", T_FLAG, OFF(single_scatter), 0, 0, JD_OPT_REFERENCE, "           trace the light scattered once along each camera ray, in place of the light carried across thin parts (--eta 1 only)"},
    {"--volume", T_FLAG, OFF(volume), 0, 0, JD_OPT_REFERENCE, "           solve the diffusion equation in the body on a grid (light round bends, through thick parts) instead of summing the dipole"},
    {"--volume-mm", T_FLOAT, OFF(volume_mm), 0.05, 100, JD_OPT_REFERENCE, "X          the volume's cells, mm (implies --volume) [the finest that keeps 6 million cells in the box around the object, at least 0.25]"},
    {"--threads", T_INT, OFF(threads), 1, 256, JD_OPT_REFERENCE, "N          [every core]"},
    {"--seed", T_INT, OFF(seed), 0, 1000000000, JD_OPT_REFERENCE, "N          sample placement [0]"},
    {"--quiet", T_FLAG, OFF(quiet), 0, 0, JD_OPT_REFERENCE, "           no progress bar"},
    {"--mask", T_PATH, OFF(mask_in), 0, 0, JD_OPT_METRIC, "FILE.png   the object's pixels (nonzero) [where either picture differs from its corner]"},
    {"--screenshot", T_PATH, OFF(screenshot), 0, 0, V | K,
     "FILE.png   view: write the last frame (with --frames); kiosk: at the end, what the display scans out, read back by its writeback connector (drm)"},
    {"--platform", T_STR, OFF(platform), 0, 0, K, "P          drm [default], x11 or headless"},
    {"--drm-device", T_PATH, OFF(drm_device), 0, 0, K, "PATH       [the first KMS-capable /dev/dri/card*]"},
    {"--connector", T_STR, OFF(connector), 0, 0, K, "NAME       e.g. HDMI-A-1 [the first connected]"},
    {"--display-mode", T_STR, OFF(display_mode), 0, 0, K, "WxH[@Hz]   [the preferred mode, else the largest]"},
    {"--config", T_PATH, OFF(config), 0, 0, K, "FILE       options as 'key = value' lines (keys as these options, without --); re-read on SIGHUP"},
    {"--idle", T_FLOAT, OFF(idle_s), 0, 86400, K, "S          after S seconds without touch or mouse the camera returns to its place [30]"},
    {"--wait-display", T_FLAG, OFF(wait_display), 0, 0, K, "           no display yet (or held by another): wait for one, retrying every second"},
    {"--kms", T_KMS, OFF(kms), 0, 0, K,
     "API        auto|atomic|legacy: atomic modesetting where the driver has it (the display engine may then enlarge the tier's smaller picture), else legacy [auto]"},
    {"--atomic", T_FLAG, OFF(atomic), 0, 0, K, "           the same as --kms atomic: fail where the driver has no atomic modesetting"},
    {"--gpu-enlarge", T_FLAG, OFF(gpu_enlarge), 0, 0, K, "           the GPU enlarges the tier's smaller picture even where the display engine's scaler could"},
    {"--rotate", T_INT, OFF(rotation), 0, 270, K | RO, "DEG        0, 90, 180 or 270, counter-clockwise as DRM (portrait panels) [0]"},
    {"--size", T_SIZE, 0, 16, 4096, RO | V | K | B | JD_OPT_REFERENCE, "WxH        image or window size (drm: the mode) [512x512]"},
    {"--frames", T_INT, OFF(frames), 1, 100000000, R | B | JD_OPT_REFERENCE, "N          frames [render, reference 1, bench 200, view/kiosk: until closed]"},
    {"--mode", T_MODE, OFF(mode_list), 0, 0, R | B, "M          none|single|dual|full [full]; bench also all [bench: all]"},
    {"--material", T_STR, OFF(material), 0, 0, S, "NAME       measured material (jade info --materials) [the file's glTF extras.jade_material, else marble]"},
    {"--sigma-s", T_FLOAT3, OFF(scene.sigma_s), 0, 1000, S, "R,G,B      reduced scattering, mm^-1"},
    {"--sigma-a", T_FLOAT3, OFF(scene.sigma_a), 0, 1000, S, "R,G,B      absorption, mm^-1"},
    {"--eta", T_FLOAT, OFF(scene.eta), 1.0, 3.0, S, "X          refractive index"},
    {"--density", T_FLOAT, OFF(scene.density), 0.001, 1000, S, "X          scales both coefficients [1]"},
    {"--mm-per-unit", T_FLOAT, OFF(scene.mm_per_unit), 1e-6, 1e9, S, "X          scene scale [object 100 mm across]"},
    {"--gain", T_FLOAT, OFF(scene.gain), 0, 100, R | B, "K          gain of the translucent layer [1]"},
    {"--yaw", T_FLOAT, OFF(scene.cam_azimuth), -3600, 3600, S, "DEG        camera around +Y [15]"},
    {"--pitch", T_FLOAT, OFF(scene.cam_elevation), -89, 89, S, "DEG        camera elevation [35]"},
    {"--fit", T_FLOAT, OFF(scene.fit), 0.05, 1, S, "X          the camera frames the object's box within X of the picture [0.9]"},
    {"--distance", T_FLOAT, OFF(scene.cam_distance), 1.3, 100, S, "X          camera distance in half box diagonals, instead of --fit [fit]"},
    {"--cam-azimuth", T_FLOAT, OFF(scene.cam_azimuth), -3600, 3600, S, "DEG        the same as --yaw"},
    {"--cam-elevation", T_FLOAT, OFF(scene.cam_elevation), -89, 89, S, "DEG        the same as --pitch"},
    {"--cam-distance", T_FLOAT, OFF(scene.cam_distance), 1.3, 100, S, "X          the same as --distance"},
    {"--fov", T_FLOAT, OFF(scene.fov_deg), 5, 150, S, "DEG        vertical field of view [35]"},
    {"--light-azimuth", T_FLOAT, OFF(scene.light_azimuth), -3600, 3600, S, "DEG        light around +Y [170: behind]"},
    {"--light-elevation", T_FLOAT, OFF(scene.light_elevation), -89, 89, S, "DEG        light elevation [35]"},
    {"--light-intensity", T_FLOAT, OFF(scene.light_intensity), 0, 100, S, "X          [1]"},
    {"--exposure", T_FLOAT, OFF(scene.exposure), 0.01, 100, S, "X          [1]"},
    {"--ambient", T_FLOAT, OFF(scene.ambient), 0, 100, S, "X          irradiance from every direction, unshadowed, in the light's units [0.06]"},
    {"--specular", T_FLOAT, OFF(scene.specular), 0, 100, S, "X          the highlight's strength (0: none) [0.2]"},
    {"--cube-size", T_INT, OFF(rdesc.cube_size), 8, 256, R | B, "N          capture face size, multiple of 8 [64]"},
    {"--light-map", T_INT, OFF(rdesc.light_map_size), 16, 2048, R | B, "N          light depth map size, a power of two [256]"},
    {"--proxy-cells", T_INT, OFF(rdesc.proxy_cells), 4, 64, R | B, "N          proxy mesh grid [40]"},
    {"--spread-divisor", T_INT, OFF(rdesc.spread_divisor), 1, 16, R | B, "N          spread layers at 1/N resolution [8]"},
    {"--diffusion-size", T_INT, OFF(rdesc.diffusion_size), 16, 2048, R | B, "N          full mode: first light-space diffusion level, texels per side, a power of two from light map / 16 [light map / 4]"},
    {"--compile", T_FLAG, OFF(compile_only), 0, 0, JD_OPT_INFO,
     "           build every shader program of every mode (as the renderer would for this device or --profile), draw nothing; a table, exit 1 if one fails"},
    {"--boards", T_FLAG, OFF(list_boards), 0, 0, JD_OPT_INFO, "           list the boards of the frame-cost model (bench --device) and their constants' sources"},
    {"--unroll-loops", T_INT, OFF(unroll_loops), 0, 8, JD_OPT_INFO,
     "N          with --compile: dynamic loops at a constant N trips (tools/device-shaders.sh: the cost of a trip) [0: as shipped]"},
    {"--materials", T_FLAG, OFF(list_materials), 0, 0, JD_OPT_INFO, "           list the measured materials, their coefficients and where they come from"},
    {"--profile", T_STR, OFF(profile), 0, 0, R | B | JD_OPT_INFO, "NAME       emulate a device's limits: generic, vc4, mali400, vivante, adreno3xx, gc7000l"},
    {"--device", T_STR, OFF(device), 0, 0, B,
     "BOARD      draw with the board's profile and estimate each mode's frame there (jade info --boards)"},
    {"--precision", T_PRECISION, OFF(rdesc.precision), 0, 0, R | B, "P          auto|highp|mediump packing [auto]"},
    {"--antialias", T_ANTIALIAS, OFF(rdesc.antialias), 0, 0, R | B,
     "A          auto|off|post: edges by the target's multisampling, else a pass after the frame [auto]"},
    {"--program-probe", T_PROBE, OFF(rdesc.program_probe), 0, 0, R | B,
     "P          auto|on|off: draw every shader program once at start-up to find ones the driver drops [auto: GPUs, not llvmpipe]"},
    {"--render-scale", T_FLOAT, OFF(rdesc.render_scale), 0.25, 1, R | B,
     "X          draw the picture at X of its size and enlarge it [the device's tier: 1, less on Mali-400 and VideoCore IV from 1280x960]"},
    {"--fragment-thickness", T_FLAG, OFF(rdesc.fragment_thickness), 0, 0, R | B, "           thickness per fragment, not per vertex (coarse meshes)"},
    {"--levels", T_LEVELS, OFF(rdesc.levels), 0, 0, R | B,
     "L          auto|vertex|fragment: where full sums its diffusion levels [auto: by the GPU and the mesh's vertices]"},
    {"--no-cull", T_FLAG, OFF(rdesc.no_cull), 0, 0, R | B, "           draw back faces (open meshes)"},
    {"--light-speed", T_FLOAT, OFF(light_speed), -3600, 3600, K,
     "DEG/S      the light's orbit [30: once every 12 s]; 0: still, and the light-space passes are reused"},
    {"--light-step", T_FLOAT, OFF(light_step), -360, 360, RO | JD_OPT_REFERENCE,
     "DEG        the light turns DEG from one frame to the next [0]; with %d in --out every frame is written"},
    {"--log-every", T_FLOAT, OFF(log_every), 0, 86400, K | B,
     "S          a health line every S seconds: frames, frame times, missed vblanks, memory, fds, GL names [0: off]"},
    {"--cycle-materials", T_FLAG, OFF(cycle_materials), 0, 0, B, "           bench: a different material every 10 frames (soak tests)"},
    {"--budget-mb", T_INT, OFF(budget_mb), 1, 4096, S | JD_OPT_CONVERT, "N          memory budget, fixed [8 + the output pictures, doubled until the mesh fits]"},
    {"--decode-timeout-ms", T_INT, OFF(load.timeout_ms), 1, 600000, S | JD_OPT_CONVERT, "N          refuse a mesh whose decode takes longer [1500 + 1000 a MiB + 5 a thousand triangles]"},
    {"--max-faces", T_INT, OFF(load.max_faces), 1, 100000000, S | JD_OPT_CONVERT, "N          refuse meshes with more faces [4000000]"},
    {"--simplify", T_INT, OFF(load.simplify_to), 64, 100000000, S | JD_OPT_CONVERT,
     "N          a mesh of more triangles is simplified towards N as it loads (meshoptimizer; a scan's million bind a Mali-400's vertex processor) [0: as the file has them]"},
};
#undef R
#undef S
#undef B
#undef RO
#undef V
#undef K

float jd_options_light_at(float azimuth, float step, long frame)
{
    return (float)((double)azimuth + (double)step * (double)frame);
}

void jd_options_defaults(jd_options *o)
{
    memset(o, 0, sizeof *o);
    o->width = o->height = 512;
    o->budget_mb = 8;
    o->material = "marble";
    jd_scene_defaults(&o->scene, jd_material_find("marble"));
    o->scene.eta = 0; /* 0 until --eta or the material sets it */
    o->light_speed = 30.0f;
    o->idle_s = 30.0f;
}

void jd_options_help(int command, const char *cmdname, const char *summary)
{
    printf("usage: jade %s %s[options]\n%s\n\noptions:\n", cmdname,
           (command & JD_OPT_METRIC) ? "A B " : (command & JD_OPT_CONVERT) ? "IN OUT.drc " : "", summary);
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (table[i].commands & command) printf("  %-20s %s\n", table[i].name, table[i].help);
    printf("  %-20s %s\n", "--help", "           this text");
    if (command & (JD_OPT_RENDER | JD_OPT_BENCH | JD_OPT_REFERENCE)) {
        printf("\nmaterials:");
        for (int m = 0; m < jd_material_count; m++) printf(" %s", jd_materials[m].name);
        printf("\n");
    }
}

static int parse_double(const char *s, double lo, double hi, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || end == s || *end || !isfinite(v) || v < lo || v > hi) return 0;
    *out = v;
    return 1;
}

/* A whole decimal number from `*s` up to a character in `stop` (or the
 * end): no sign games, no wraparound (4294967312 is not 16). */
static int parse_whole(const char **s, const char *stop, long lo, long hi, long *out)
{
    const char *p = *s;
    long v = 0;
    if (*p < '0' || *p > '9') return 0;
    for (; *p >= '0' && *p <= '9'; p++) {
        if (v > (hi - (*p - '0')) / 10) return 0; /* past hi: stop before overflowing */
        v = v * 10 + (*p - '0');
    }
    if (*p && !strchr(stop, *p)) return 0;
    if (v < lo) return 0;
    *s = p;
    *out = v;
    return 1;
}

/* Edit distance, for "did you mean": option names are short. */
static int distance(const char *a, const char *b)
{
    int row[64], la = (int)strlen(a), lb = (int)strlen(b);
    if (la > 63 || lb > 63) return 99;
    for (int j = 0; j <= lb; j++) row[j] = j;
    for (int i = 1; i <= la; i++) {
        int diag = row[0];
        row[0] = i;
        for (int j = 1; j <= lb; j++) {
            int up = row[j], best = diag + (a[i - 1] != b[j - 1]);
            if (up + 1 < best) best = up + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            diag = up;
            row[j] = best;
        }
    }
    return row[lb];
}

static const opt *find_option(int command, const char *name, size_t len)
{
    for (size_t k = 0; k < sizeof table / sizeof table[0]; k++)
        if ((table[k].commands & command) && strlen(table[k].name) == len && !strncmp(name, table[k].name, len))
            return &table[k];
    return NULL;
}

static void unknown_option(int command, const char *cmd, const char *a, size_t len)
{
    const char *best = NULL;
    int bd = 4;
    char name[64];
    snprintf(name, sizeof name, "%.*s", (int)(len < 63 ? len : 63), a);
    for (size_t k = 0; k < sizeof table / sizeof table[0]; k++) {
        if (!(table[k].commands & command)) continue;
        int d = distance(name, table[k].name);
        if (d < bd) { bd = d; best = table[k].name; }
    }
    /* The command's name alone ("kiosk: FILE line N" names a config line). */
    int cl = (int)strcspn(cmd, ": ");
    if (best)
        fprintf(stderr, "jade %s: unknown option '%.*s'; did you mean %s? (see jade %.*s --help)\n", cmd, (int)len, a,
                best, cl, cmd);
    else
        fprintf(stderr, "jade %s: unknown option '%.*s' (see jade %.*s --help)\n", cmd, (int)len, a, cl, cmd);
}

/* A path the system could not open as given is refused here, by name,
 * rather than cut to fit a buffer (a cut path may name another file). */
static int path_ok(const char *cmd, const char *what, const char *v)
{
    if (!*v) {
        fprintf(stderr, "jade %s: %s: empty path\n", cmd, what);
        return 0;
    }
    if (strlen(v) >= PATH_MAX) {
        fprintf(stderr, "jade %s: %s: a path of %zu bytes, longer than the system allows (%d)\n", cmd, what,
                strlen(v), PATH_MAX - 1);
        return 0;
    }
    return 1;
}

int jd_options_parse(jd_options *o, int command, const char *cmd, int argc, char **argv, int first)
{
    int options_done = 0;
    for (int i = first; i < argc; i++) {
        const char *a = argv[i];
        if (!options_done && (!strcmp(a, "--help") || !strcmp(a, "-h"))) return -1;
        if ((options_done || a[0] != '-' || !a[1]) && (command & (JD_OPT_METRIC | JD_OPT_CONVERT))) {
            /* metric's two pictures, convert's input and output */
            const char *what = (command & JD_OPT_METRIC) ? "picture" : "file";
            if (o->num_positional >= 2) {
                fprintf(stderr, "jade %s: one %s too many: '%s'\n", cmd, what, a);
                return 0;
            }
            if (!path_ok(cmd, what, a)) return 0;
            o->positional[o->num_positional++] = a;
            continue;
        }
        if (!strcmp(a, "--") && (command & (JD_OPT_METRIC | JD_OPT_CONVERT))) { options_done = 1; continue; }
        /* --name value, or --name=value */
        const char *eq = strncmp(a, "--", 2) ? NULL : strchr(a, '=');
        size_t len = eq ? (size_t)(eq - a) : strlen(a);
        const opt *op = find_option(command, a, len);
        if (!op) {
            unknown_option(command, cmd, a, len);
            return 0;
        }
        char *field = (char *)o + op->offset;
        if (op->type == T_FLAG) {
            if (eq) { fprintf(stderr, "jade %s: %s takes no value\n", cmd, op->name); return 0; }
            *(int *)field = 1;
            continue;
        }
        const char *v;
        if (eq) {
            v = eq + 1;
        } else if (i + 1 < argc) {
            v = argv[++i];
        } else {
            fprintf(stderr, "jade %s: %s needs a value (see jade %s --help)\n", cmd, a, cmd);
            return 0;
        }
        a = op->name;
        double d;
        switch (op->type) {
        case T_STR:
            if (!*v) { fprintf(stderr, "jade %s: %s: empty value\n", cmd, a); return 0; }
            *(const char **)field = v;
            if (op->offset == OFF(material)) o->has_material = 1;
            break;
        case T_PATH:
            if (!path_ok(cmd, a, v)) return 0;
            *(const char **)field = v;
            break;
        case T_INT:
            if (!parse_double(v, op->lo, op->hi, &d) || d != floor(d)) {
                fprintf(stderr, "jade %s: %s: expected a whole number from %.0f to %.0f, got '%s'\n", cmd, a, op->lo, op->hi, v);
                return 0;
            }
            *(int *)field = (int)d;
            if (op->offset == OFF(budget_mb)) o->has_budget = 1;
            break;
        case T_FLOAT:
            if (!parse_double(v, op->lo, op->hi, &d)) {
                fprintf(stderr, "jade %s: %s: expected a number from %g to %g, got '%s'\n", cmd, a, op->lo, op->hi, v);
                return 0;
            }
            *(float *)field = (float)d;
            if (op->offset == OFF(scene.eta)) o->has_eta = 1;
            break;
        case T_FLOAT3: {
            /* Three numbers split in place: any length, nothing cut. */
            float *f3 = (float *)field, got[3];
            const char *p = v;
            int n = 0, ok = 1;
            while (ok && n < 3) {
                char *end;
                errno = 0;
                double x = strtod(p, &end);
                ok = end != p && !errno && isfinite(x) && x >= op->lo && x <= op->hi &&
                     (*end == ',' ? n < 2 : *end == 0 && n == 2);
                if (ok) { got[n++] = (float)x; p = *end ? end + 1 : end; }
            }
            if (!ok || n != 3) {
                fprintf(stderr, "jade %s: %s: expected three numbers R,G,B from %g to %g, got '%s'\n", cmd, a, op->lo, op->hi, v);
                return 0;
            }
            memcpy(f3, got, sizeof got);
            if (op->offset == OFF(scene.sigma_s)) o->has_sigma_s = 1; else o->has_sigma_a = 1;
            break;
        }
        case T_SIZE: {
            long w = 0, h = 0;
            const char *p = v;
            int ok = parse_whole(&p, "x", (long)op->lo, (long)op->hi, &w) && *p == 'x';
            if (ok) { p++; ok = parse_whole(&p, "", (long)op->lo, (long)op->hi, &h) && !*p; }
            if (!ok) {
                fprintf(stderr, "jade %s: %s: expected WxH from 16x16 to 4096x4096, got '%s'\n", cmd, a, v);
                return 0;
            }
            o->width = (int)w;
            o->height = (int)h;
            break;
        }
        case T_MODE: {
            jd_mode m;
            if (!strcmp(v, "all") && (command & JD_OPT_BENCH)) { o->mode_list = v; break; }
            if (!jd_mode_parse(v, &m)) {
                fprintf(stderr, "jade %s: %s: expected none, single, dual or full%s, got '%s'\n", cmd, a,
                        (command & JD_OPT_BENCH) ? " or all" : "", v);
                return 0;
            }
            o->mode_list = v;
            o->scene.mode = m;
            break;
        }
        case T_PRECISION:
        case T_ANTIALIAS:
        case T_PROBE:
        case T_KMS:
        case T_LEVELS: {
            /* The words in the enums' order (jd_precision, jd_antialias, jd_probe, jd_kms_api, jd_levels). */
            static const char *const words[][3] = {{"auto", "highp", "mediump"},
                                                   {"auto", "off", "post"},
                                                   {"auto", "on", "off"},
                                                   {"auto", "atomic", "legacy"},
                                                   {"auto", "vertex", "fragment"}};
            const char *const *w = words[op->type - T_PRECISION];
            int k = 0;
            while (k < 3 && strcmp(v, w[k])) k++;
            if (k == 3) {
                fprintf(stderr, "jade %s: %s: expected %s, %s or %s, got '%s'\n", cmd, a, w[0], w[1], w[2], v);
                return 0;
            }
            if (op->type == T_PRECISION) o->rdesc.precision = (jd_precision)k;
            else if (op->type == T_ANTIALIAS) o->rdesc.antialias = (jd_antialias)k;
            else if (op->type == T_PROBE) o->rdesc.program_probe = (jd_probe)k;
            else if (op->type == T_LEVELS) o->rdesc.levels = (jd_levels)k;
            else o->kms = k;
            break;
        }
        case T_FLAG:
            break;
        }
    }
    return 1;
}

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t') s++;
    char *e = s + strlen(s);
    while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r')) *--e = 0;
    return s;
}

int jd_options_parse_file(jd_options *o, int command, const char *cmd, const char *path, char *store, size_t cap)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    struct stat st;
    if (fd < 0) {
        fprintf(stderr, "jade %s: %s: cannot open: %s\n", cmd, path, strerror(errno));
        return 0;
    }
    int regular = fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
    if (!regular || (size_t)st.st_size >= cap) {
        fprintf(stderr, "jade %s: %s: %s\n", cmd, path,
                !regular ? "not a regular file" : "larger than a configuration file may be (64 KiB)");
        close(fd);
        return 0;
    }
    size_t n = 0;
    while (n < (size_t)st.st_size) {
        ssize_t k = read(fd, store + n, (size_t)st.st_size - n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) break;
        n += (size_t)k;
    }
    close(fd);
    store[n] = 0;
    if (memchr(store, 0, n)) {
        fprintf(stderr, "jade %s: %s: holds a NUL byte; not a text file\n", cmd, path);
        return 0;
    }
    int line = 0;
    for (char *p = store; p && *p;) {
        char *next = strchr(p, '\n');
        if (next) *next++ = 0;
        line++;
        char *hash = strchr(p, '#');
        if (hash) *hash = 0;
        char *l = trim(p);
        p = next;
        if (!*l) continue;
        char *eq = strchr(l, '=');
        char where[PATH_MAX + 64];
        snprintf(where, sizeof where, "%s: %s line %d", cmd, path, line);
        if (!eq) {
            fprintf(stderr, "jade %s: expected 'key = value', got '%s'\n", where, l);
            return 0;
        }
        *eq = 0;
        char *key = trim(l), *value = trim(eq + 1);
        char name[72];
        if (!*key || strlen(key) > 60 || !strncmp(key, "--", 2)) {
            fprintf(stderr, "jade %s: '%s' is not an option name (write them without --)\n", where, key);
            return 0;
        }
        snprintf(name, sizeof name, "--%s", key);
        const opt *op = find_option(command, name, strlen(name));
        if (op && op->type == T_FLAG) {
            if (!strcmp(value, "no") || !strcmp(value, "false") || !strcmp(value, "off") || !strcmp(value, "0")) {
                *(int *)((char *)o + op->offset) = 0;
                continue;
            }
            if (strcmp(value, "yes") && strcmp(value, "true") && strcmp(value, "on") && strcmp(value, "1")) {
                fprintf(stderr, "jade %s: %s takes yes or no, got '%s'\n", where, key, value);
                return 0;
            }
        }
        if (op && op->offset == OFF(config)) {
            fprintf(stderr, "jade %s: a configuration file cannot name another\n", where);
            return 0;
        }
        /* Values stay in `store`, which the options point into. */
        char *argv[4] = {NULL, NULL, name, value};
        int argc = op && op->type == T_FLAG ? 3 : 4;
        if (jd_options_parse(o, command, where, argc, argv, 2) != 1) return 0;
    }
    return 1;
}

int jd_options_finish(jd_options *o, const char *cmd)
{
    const jd_material *m = jd_material_find(o->material);
    if (!m) {
        fprintf(stderr, "jade %s: --material: unknown material '%s' (see jade %s --help)\n", cmd, o->material, cmd);
        return 0;
    }
    if (o->profile && !jd_profile_find(o->profile)) {
        /* The names from the one list of profiles (core/profile.c). */
        char have[128] = "";
        for (int i = 0; i < jd_profile_count; i++)
            snprintf(have + strlen(have), sizeof have - strlen(have), "%s%s", i ? ", " : "", jd_profiles[i].name);
        fprintf(stderr, "jade %s: --profile: unknown profile '%s' (have: %s)\n", cmd, o->profile, have);
        return 0;
    }
    if (o->device) {
        const jd_board *b = jd_board_find(o->device);
        if (!b) {
            char have[128] = "";
            for (int i = 0; i < jd_board_count; i++)
                snprintf(have + strlen(have), sizeof have - strlen(have), "%s%s", i ? ", " : "", jd_boards[i].name);
            fprintf(stderr, "jade %s: --device: unknown board '%s' (have: %s)\n", cmd, o->device, have);
            return 0;
        }
        if (o->profile && strcmp(o->profile, b->profile)) {
            fprintf(stderr, "jade %s: --device %s draws with profile %s, not --profile %s\n", cmd, b->name, b->profile,
                    o->profile);
            return 0;
        }
        o->profile = b->profile;
    }
    if (!o->has_sigma_s) memcpy(o->scene.sigma_s, m->sigma_s, sizeof m->sigma_s);
    if (!o->has_sigma_a) memcpy(o->scene.sigma_a, m->sigma_a, sizeof m->sigma_a);
    if (!o->has_eta) o->scene.eta = m->eta;
    if (o->rotation % 90) {
        fprintf(stderr, "jade %s: --rotate: %d is not 0, 90, 180 or 270\n", cmd, o->rotation);
        return 0;
    }
    if (o->rdesc.cube_size && o->rdesc.cube_size % 8) {
        fprintf(stderr, "jade %s: --cube-size: %d is not a multiple of 8\n", cmd, o->rdesc.cube_size);
        return 0;
    }
    return 1;
}

static void file_medium(jd_options *o, const jd_file_medium *m, const char *path, const char *cmd)
{
    int say = !o->medium_said;
    o->medium_said = 1;
    if (say && m->ignored[0]) fprintf(stderr, "jade %s: %s: jade does not show %s\n", cmd, path, m->ignored);
    if (o->has_material || !(m->flags & (JD_MEDIUM_SIGMA | JD_MEDIUM_ETA))) return;
    if (m->flags & JD_MEDIUM_SIGMA) {
        if (!o->has_sigma_s) memcpy(o->scene.sigma_s, m->sigma_s, sizeof m->sigma_s);
        if (!o->has_sigma_a) memcpy(o->scene.sigma_a, m->sigma_a, sizeof m->sigma_a);
        /* The coefficients are per millimetre of the file's own unit. */
        if (o->scene.mm_per_unit <= 0.0f && m->mm_per_unit > 0.0f) o->scene.mm_per_unit = m->mm_per_unit;
        o->material = "gltf";
    }
    if ((m->flags & JD_MEDIUM_ETA) && !o->has_eta) o->scene.eta = m->eta;
    if (say)
        fprintf(stderr,
                "jade %s: %s: the material of %s: sigma_s' %.4g %.4g %.4g, sigma_a %.4g %.4g %.4g per mm, eta %.3g, "
                "%g mm a unit\n",
                cmd, path, m->source, (double)o->scene.sigma_s[0], (double)o->scene.sigma_s[1],
                (double)o->scene.sigma_s[2], (double)o->scene.sigma_a[0], (double)o->scene.sigma_a[1],
                (double)o->scene.sigma_a[2], (double)o->scene.eta, (double)o->scene.mm_per_unit);
}

/* A model whose file gives its surface colours and no material: the
 * material whose diffuse reflectance is their mean, with the current
 * material's (marble's) diffuse mean free path (docs/textures.md). */
static void file_colour(jd_options *o, const jd_load_stats *st, const char *path, const char *cmd)
{
    if (o->has_material || !st->coloured || (st->medium.flags & JD_MEDIUM_SIGMA) || st->material[0]) return;
    if (o->has_sigma_s || o->has_sigma_a) return;
    jd_dipole d;
    jd_dipole_init(&d, o->scene.sigma_s, o->scene.sigma_a, o->scene.eta, 1.0f);
    float ld[3];
    for (int c = 0; c < 3; c++) ld[c] = d.sigma_tr[c] > 0 ? (float)(1.0 / d.sigma_tr[c]) : 1e3f;
    jd_material_from_reflectance(st->albedo_mean, ld, o->scene.eta, o->scene.sigma_s, o->scene.sigma_a);
    if (!o->colour_said)
        fprintf(stderr,
                "jade %s: %s: the material from the model's colours (mean reflectance %.3g %.3g %.3g) with %s's mean "
                "free path: sigma_s' %.4g %.4g %.4g, sigma_a %.4g %.4g %.4g per mm\n",
                cmd, path, (double)st->albedo_mean[0], (double)st->albedo_mean[1], (double)st->albedo_mean[2],
                o->material, (double)o->scene.sigma_s[0], (double)o->scene.sigma_s[1], (double)o->scene.sigma_s[2],
                (double)o->scene.sigma_a[0], (double)o->scene.sigma_a[1], (double)o->scene.sigma_a[2]);
    o->colour_said = 1;
    o->material = "colour";
}

void jd_options_file_material(jd_options *o, const jd_load_stats *st, const char *path, const char *cmd)
{
    file_medium(o, &st->medium, path, cmd);
    file_colour(o, st, path, cmd);
    const char *name = st->material;
    if (o->has_material || !name || !name[0]) return;
    const jd_material *m = jd_material_find(name);
    if (!m) {
        fprintf(stderr, "jade %s: the mesh names material '%s', which jade does not have; using %s\n", cmd, name,
                o->material);
        return;
    }
    o->material = m->name;
    if (!o->has_sigma_s) memcpy(o->scene.sigma_s, m->sigma_s, sizeof m->sigma_s);
    if (!o->has_sigma_a) memcpy(o->scene.sigma_a, m->sigma_a, sizeof m->sigma_a);
    if (!o->has_eta) o->scene.eta = m->eta;
}

int jd_options_command(jd_options *o, int command, const char *cmd, const char *summary, int argc, char **argv)
{
    int p = jd_options_parse(o, command, cmd, argc, argv, 2);
    if (p < 0) {
        jd_options_help(command, cmd, summary);
        return 0;
    }
    if (!p || !jd_options_finish(o, cmd)) return 2;
    return -1;
}
