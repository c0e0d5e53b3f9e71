/* The scene's physics on the CPU: defaults, where the camera and the light
 * are, and what the material makes of light (the dipole's constants and
 * the blends the passes use). No GL: the renderer and anything that must
 * show the same picture (jade reference) share it. */
#include "scene.h"

#include <math.h>
#include <string.h>

#include "vmath.h"

const char *jd_mode_name(jd_mode m)
{
    static const char *names[] = {"none", "single", "dual", "full"};
    return m >= 0 && m < JD_MODE_COUNT ? names[m] : "?";
}

int jd_mode_parse(const char *s, jd_mode *out)
{
    for (int m = 0; m < JD_MODE_COUNT; m++)
        if (strcmp(s, jd_mode_name((jd_mode)m)) == 0) { *out = (jd_mode)m; return 1; }
    return 0;
}

const char *jd_pass_name(int pass)
{
    static const char *names[] = {"light_depth", "capture", "sh_reduce", "spread", "diffusion", "main"};
    return pass >= 0 && pass < JD_PASS_COUNT ? names[pass] : "?";
}

void jd_scene_defaults(jd_scene *s, const jd_material *m)
{
    memset(s, 0, sizeof *s);
    s->mode = JD_MODE_FULL;
    s->cam_azimuth = 15;
    s->cam_elevation = 35;
    s->cam_distance = 0; /* fit the object to the picture */
    s->fit = 0.9f;
    s->fov_deg = 35;
    s->light_azimuth = 170; /* behind the object: what translucency is about */
    s->light_elevation = 35;
    s->light_intensity = 1.0f;
    s->ambient = 0.06f;
    s->specular = 0.2f;
    s->shininess = 40;
    s->exposure = 1.0f;
    if (!m) m = jd_material_find("marble");
    memcpy(s->sigma_s, m->sigma_s, sizeof s->sigma_s);
    memcpy(s->sigma_a, m->sigma_a, sizeof s->sigma_a);
    s->eta = m->eta;
    s->density = 1.0f;
    s->gain = 1.0f;
    s->background[0] = 0.05f;
    s->background[1] = 0.055f;
    s->background[2] = 0.065f;
}

/* The nearest camera distance, along `dir` (unit, from the origin to the
 * camera), at which every corner of the box (world units, centred) projects
 * within `fit` of the picture, on both sides: for a corner at right/up
 * offsets x, y and depth z towards the camera, |x| <= fit * tx * (d - z) and
 * the same for y. A figure standing in a portrait frame fills its height;
 * nothing is cropped at any aspect or angle. */
static float fit_distance(jd_vec3 half, jd_vec3 dir, float fit, float fov_deg, float aspect)
{
    if (!(fit > 0 && fit <= 1)) fit = 0.9f;
    double ty = tan(fov_deg * M_PI / 360.0) * fit, tx = ty * aspect;
    jd_vec3 up = fabsf(dir.y) > 0.999f ? jd_v3(1, 0, 0) : jd_v3(0, 1, 0);
    jd_vec3 right = jd_v3_norm(jd_v3_cross(up, dir)), u = jd_v3_cross(dir, right);
    double d = 0;
    for (int k = 0; k < 8; k++) {
        jd_vec3 p = jd_v3(k & 1 ? half.x : -half.x, k & 2 ? half.y : -half.y, k & 4 ? half.z : -half.z);
        double x = fabs(jd_v3_dot(p, right)), y = fabs(jd_v3_dot(p, u)), z = jd_v3_dot(p, dir);
        d = fmax(d, fmax(z + x / tx, z + y / ty));
    }
    return (float)fmax(d, 1.3); /* the near plane stays in front of the object */
}

void jd_scene_view_of(const jd_scene *s, const jd_mesh *m, float aspect, jd_scene_view *v)
{
    jd_mesh_placement(m, &v->centre, &v->radius);
    float mm_per_unit = s->mm_per_unit > 0 ? s->mm_per_unit : 100.0f / (2.0f * v->radius);
    v->mm_per_world = mm_per_unit * v->radius;
    v->fov_deg = s->fov_deg > 1 ? s->fov_deg : 35.0f;
    jd_vec3 dir = jd_v3_from_angles(s->cam_azimuth, s->cam_elevation);
    jd_vec3 half = jd_v3_scale(jd_v3_sub(m->bmax, m->bmin), 0.5f / v->radius);
    v->cam_distance = s->cam_distance > 0 ? s->cam_distance
                                          : fit_distance(half, dir, s->fit, v->fov_deg, aspect > 0 ? aspect : 1.0f);
    v->eye = jd_v3_scale(dir, v->cam_distance);
    v->light_dir = jd_v3_from_angles(s->light_azimuth, s->light_elevation);
    v->eta = s->eta > 0.5f ? s->eta : 1.3f;
    float f0 = (v->eta - 1.0f) / (v->eta + 1.0f);
    v->f0 = f0 * f0;
    v->shininess = s->shininess > 1 ? s->shininess : 1;
    v->exposure = s->exposure > 0 ? s->exposure : 1;
}

void jd_scene_optics_of(const jd_scene *s, const jd_scene_view *sv, jd_scene_optics *o)
{
    double density = s->density > 0 ? s->density : 1.0;
    jd_dipole_init(&o->dipole, s->sigma_s, s->sigma_a, sv->eta, (float)density);
    o->mean_sigma_s = 0;
    for (int c = 0; c < 3; c++) {
        o->albedo[c] = (float)o->dipole.rd_total[c];
        o->a0_scale[c] = (float)(s->gain * (1.0 - o->dipole.fdr) / M_PI * 0.5 * o->dipole.alpha[c]);
        /* The paper's blend, per channel, with sigma_s' (density-scaled). */
        double sig = s->sigma_s[c] * density;
        o->w0[c] = (float)(1.0 / (1.0 + 3.0 * sig));
        o->w1[c] = (float)(2.0 * sig / (1.0 + 3.0 * sig));
        o->w2[c] = (float)(sig / (1.0 + 3.0 * sig));
        o->mean_sigma_s += sig / 3.0;
    }
}
