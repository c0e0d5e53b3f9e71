#define _GNU_SOURCE
#include "ref_render.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "clock.h"
#include "display_curve.h"
#include "halfspace_albedo.h"
#include "material.h"
#include "progress.h"
#include "ref_bvh.h"
#include "ref_diffusion.h"
#include "ref_samples.h"
#include "ref_single.h"
#include "ref_slab.h"
#include "ref_volume.h"
#include "ray_fan.h"

enum { JD_BEAM_STEPS = 64 }; /* the beam's albedo table: its cosine in 64 steps */

struct jd_ref {
    jd_ref_desc d;
    float *pos;          /* normalised world positions */
    float *nrm;
    uint32_t *tri;
    uint32_t num_tris;
    jd_bvh bvh;
    jd_ref_point *pts;
    float *pt_n;         /* outward normal per sample (before the octree reorders pts) */
    /* sqrt(reflectance / mean) per sample where the model has colours (the
     * light entering there), else NULL. */
    float *pt_alb;
    jd_diffusion diff;
    jd_diffusion carry;  /* light carried across thin parts (ref_slab.h); no nodes where none is */
    jd_volume vol;       /* desc.volume: the diffusion equation in the body, in place of both */
    jd_volume_desc vd;
    jd_dipole dp;
    jd_single single;    /* desc.single_scatter: the medium's light scattered once, traced per pixel */
    /* The light's beam by its cosine (0..1 in JD_BEAM_STEPS): the
     * half-space's albedo for that beam over its albedo for diffuse light,
     * which the dipole's profile already has (jd_albedo_ratio), per channel. */
    float beam_scale[3][JD_BEAM_STEPS + 1];
    /* How the light leaves, by the cosine to the viewer (jd_halfspace_exit):
     * light from far (exit_deep) and the light's own beam where it fell
     * (exit_beam, [viewer][light] cosines), per channel. */
    float exit_deep[3][JD_BEAM_STEPS + 1];
    float exit_beam[3][(JD_BEAM_STEPS + 1) * (JD_BEAM_STEPS + 1)];
    /* The boundary's transmittance by the light's cosine over its mean for
     * diffuse light (jade's albedos are of the diffuse light that falls). */
    float entry_t[JD_BEAM_STEPS + 1];
    jd_scene_view view;
    float mm_per_world, eps;
    float light[3];
    jd_ref_stats st;
    float *ind;          /* per sample, the light other parts of the object send it (desc.bounces), or NULL */
    /* The samples as placed, in world units and in their first order (the
     * lighting turns them to millimetres, the octrees reorder them): each
     * lighting (jd_ref_relight too) and each bounce round starts again from
     * these. */
    jd_ref_point *placed;
    uint32_t n;
};

/* ---- work spread over threads --------------------------------------- */

typedef struct par_job {
    void (*fn)(void *ctx, long begin, long end, uint64_t *evals);
    void *ctx;
    long n, chunk;
    atomic_long next, done;
    atomic_ullong evals;
} par_job;

static void *par_worker(void *arg)
{
    par_job *j = arg;
    uint64_t ev = 0;
    for (;;) {
        long b = atomic_fetch_add(&j->next, j->chunk);
        if (b >= j->n) break;
        long e = b + j->chunk < j->n ? b + j->chunk : j->n;
        j->fn(j->ctx, b, e, &ev);
        atomic_fetch_add(&j->done, e - b);
    }
    atomic_fetch_add(&j->evals, ev);
    return NULL;
}

static int core_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)(n < 256 ? n : 256) : 1;
}

/* Runs fn over [0, n) in chunks on `threads` threads while the calling
 * thread draws the progress bar. Returns the evaluations counted. */
static uint64_t par_run(int threads, long n, long chunk, void (*fn)(void *, long, long, uint64_t *), void *ctx,
                        const char *label, int progress)
{
    par_job j = {.fn = fn, .ctx = ctx, .n = n, .chunk = chunk > 0 ? chunk : 1};
    atomic_init(&j.next, 0);
    atomic_init(&j.done, 0);
    atomic_init(&j.evals, 0);
    pthread_t tid[256];
    int started = 0;
    for (int i = 0; i < threads && i < 256; i++)
        if (!pthread_create(&tid[i], NULL, par_worker, &j)) started++; else break;
    jd_progress p;
    jd_progress_start(&p, label, (double)n, progress);
    if (!started) {
        par_worker(&j); /* no threads to be had: do it here */
    } else {
        while (atomic_load(&j.done) < n) {
            struct timespec ts = {0, 50 * 1000 * 1000};
            nanosleep(&ts, NULL);
            jd_progress_update(&p, (double)atomic_load(&j.done));
        }
        for (int i = 0; i < started; i++) pthread_join(tid[i], NULL);
    }
    jd_progress_finish(&p);
    return atomic_load(&j.evals);
}

/* ---- geometry ---------------------------------------------------------- */

static void tri_vertices(const jd_ref *r, uint32_t t, const float **a, const float **b, const float **c)
{
    *a = r->pos + 3 * (size_t)r->tri[3 * t];
    *b = r->pos + 3 * (size_t)r->tri[3 * t + 1];
    *c = r->pos + 3 * (size_t)r->tri[3 * t + 2];
}

static void normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0) { v[0] /= l; v[1] /= l; v[2] /= l; } else { v[0] = 0; v[1] = 0; v[2] = 1; }
}

static float dot3(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Point, interpolated normal and geometric normal at barycentrics (u, v). */
static void surface_at(const jd_ref *r, uint32_t t, float u, float v, float p[3], float n[3], float ng[3])
{
    const float *a, *b, *c;
    tri_vertices(r, t, &a, &b, &c);
    const float *na = r->nrm + 3 * (size_t)r->tri[3 * t], *nb = r->nrm + 3 * (size_t)r->tri[3 * t + 1],
                *nc = r->nrm + 3 * (size_t)r->tri[3 * t + 2];
    float w = 1 - u - v;
    for (int k = 0; k < 3; k++) {
        p[k] = w * a[k] + u * b[k] + v * c[k];
        n[k] = w * na[k] + u * nb[k] + v * nc[k];
    }
    float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    ng[0] = e1[1] * e2[2] - e1[2] * e2[1];
    ng[1] = e1[2] * e2[0] - e1[0] * e2[2];
    ng[2] = e1[0] * e2[1] - e1[1] * e2[0];
    normalize3(ng);
    if (dot3(ng, n) < 0) for (int k = 0; k < 3; k++) ng[k] = -ng[k];
    normalize3(n);
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Every edge shared by two triangles or more: no boundary. (A mesh whose
 * vertices are split along seams counts as open: its normals are then kept.) */
static int mesh_is_closed(const jd_ref *r)
{
    size_t n = 3 * (size_t)r->num_tris;
    uint64_t *e = malloc(sizeof *e * n);
    if (!e) return 0;
    for (size_t t = 0; t < r->num_tris; t++)
        for (int k = 0; k < 3; k++) {
            uint64_t a = r->tri[3 * t + k], b = r->tri[3 * t + (k + 1) % 3];
            e[3 * t + k] = a < b ? a << 32 | b : b << 32 | a;
        }
    qsort(e, n, sizeof *e, cmp_u64);
    int closed = 1;
    for (size_t i = 0; i < n && closed;) {
        size_t j = i;
        while (j < n && e[j] == e[i]) j++;
        if (j - i < 2) closed = 0;
        i = j;
    }
    free(e);
    return closed;
}

/* A model's colours (jd_mesh.colors) scale the light under its surface by
 * sqrt(A / mean A) where it enters and again where it leaves: the
 * renderer's formulation (d'Eon, Luebke and Enderton 2007's pre- and
 * post-scatter texturing), here exact at both points. */
static void albedo_factor(const jd_ref *r, uint32_t tri, float u, float v, float out[3])
{
    const jd_mesh *m = r->d.mesh;
    jd_mesh_albedo_at(m, tri, u, v, out);
    for (int k = 0; k < 3; k++) out[k] = sqrtf(out[k] / m->albedo_mean[k]);
}

/* t[0..JD_BEAM_STEPS] over the cosine c, linear between its steps. */
static float lerp_table(const float *t, float c)
{
    float x = (c > 1.0f ? 1.0f : c < 0.0f ? 0.0f : c) * JD_BEAM_STEPS;
    int i = x >= JD_BEAM_STEPS ? JD_BEAM_STEPS - 1 : (int)x;
    return t[i] + (x - (float)i) * (t[i + 1] - t[i]);
}

/* Whether the light reaches p (geometric normal ng): a shadow ray. */
static int light_visible(const jd_ref *r, const float p[3], const float ng[3])
{
    /* Leave on the light's side of the true surface. */
    float side = dot3(ng, r->light) >= 0 ? 1.0f : -1.0f, o[3];
    for (int k = 0; k < 3; k++) o[k] = p[k] + side * r->eps * ng[k];
    return !jd_bvh_occluded(&r->bvh, o, r->light, 0.0f, 1e30f);
}

/* Irradiance entering the surface at p (outward normal n, geometric ng). */
static void irradiance(const jd_ref *r, const float p[3], const float n[3], const float ng[3], float e[3])
{
    if (r->d.irradiance) { r->d.irradiance(r->d.user, p, n, e); return; }
    const jd_scene *s = &r->d.scene;
    float amb = s->ambient, direct = 0;
    float ndl = dot3(n, r->light);
    if (ndl > 0 && s->light_intensity > 0 && light_visible(r, p, ng))
        direct = s->light_intensity * ndl * lerp_table(r->entry_t, ndl);
    /* The light's own share by its angle: a beam near the normal goes
     * deeper and less of it comes back than of diffuse light (the ambient).
     * Linear between the table's cosines. */
    float x = (ndl > 1.0f ? 1.0f : ndl < 0.0f ? 0.0f : ndl) * JD_BEAM_STEPS;
    int i = x >= JD_BEAM_STEPS ? JD_BEAM_STEPS - 1 : (int)x;
    for (int c = 0; c < 3; c++) {
        float b = r->beam_scale[c][i] + (x - (float)i) * (r->beam_scale[c][i + 1] - r->beam_scale[c][i]);
        e[c] = amb + direct * b;
    }
}

/* ---- set-up ---------------------------------------------------------- */



typedef struct irr_ctx { jd_ref *r; uint32_t n; } irr_ctx;

/* Whether light is carried across thin parts: not on a half-space, not in
 * the volume's solve (its body carries it), not where single scattering is
 * traced (what came through the knot's tubes and the bunny's ears was
 * mostly that, which the slab's diffusion spread wrongly: docs/quality.md,
 * "Single scattering"). */
static int carries(const jd_ref_desc *d) { return !d->half_space && !d->volume && !d->single_scatter; }

/* Light leaving the far side of a thin part (ref_slab.h): the ray from the
 * sample along its inward normal to where it leaves the object, d mm; the
 * sample and a carried point where the ray leaves share its power by
 * jd_slab_weights (a slab's R(d) and T(d)). Where the ray leaves nothing (an
 * open mesh, a sheet) or meets a surface facing it (normals that disagree),
 * the sample stays a half-space's. */
static void carry_across(const jd_ref *r, const float pw[3], const float n[3], jd_ref_point *p, jd_ref_point *q)
{
    memset(q, 0, sizeof *q);
    q->area = p->area;
    if (p->ea[0] + p->ea[1] + p->ea[2] <= 0) return; /* no light to carry */
    float dir[3] = {-n[0], -n[1], -n[2]}, y[3], yn[3], yg[3];
    jd_hit hit;
    if (!jd_bvh_intersect(&r->bvh, pw, dir, r->eps, 1e30f, &hit)) return;
    surface_at(r, hit.tri, hit.u, hit.v, y, yn, yg);
    if (dot3(yg, dir) <= 0) return;
    double d = (double)hit.t * r->mm_per_world, carried = 0;
    for (int c = 0; c < 3; c++) {
        double ws, wc;
        jd_slab_weights(&r->dp, c, d, &ws, &wc);
        q->ea[c] = (float)(p->ea[c] * wc);
        p->ea[c] = (float)(p->ea[c] * ws);
        q->p[c] = y[c] * r->mm_per_world;
        carried += q->ea[c];
    }
    /* Past a few diffusion lengths nothing comes through: leave it out. */
    if (carried > 1e-4 * (p->ea[0] + p->ea[1] + p->ea[2])) q->thick = (float)d;
    else memset(q->ea, 0, sizeof q->ea);
}

static void irr_chunk(void *ctx, long b, long e, uint64_t *evals)
{
    jd_ref *r = ((irr_ctx *)ctx)->r;
    (void)evals;
    for (long i = b; i < e; i++) {
        jd_ref_point *p = &r->pts[i];
        float pw[3], n[3], ng[3], ei[3];
        for (int k = 0; k < 3; k++) { pw[k] = p->p[k]; n[k] = r->pt_n[6 * i + k]; ng[k] = r->pt_n[6 * i + 3 + k]; }
        irradiance(r, pw, n, ng, ei);
        if (r->ind)
            for (int k = 0; k < 3; k++) ei[k] += r->ind[3 * i + k];
        for (int k = 0; k < 3; k++) {
            p->ea[k] = ei[k] * p->area * (r->pt_alb ? r->pt_alb[3 * i + k] : 1.0f);
            p->p[k] = pw[k] * r->mm_per_world; /* the octree works in millimetres */
        }
        /* Where the light enters at a slant it goes on along its refracted
         * direction before it first scatters, 1 / sigma_t on average
         * (green's): the dipole's source sits below that point, not below
         * where it entered. Its tangential part, |l_t| / eta, moves the
         * sample (weighted by the direct light's share of its irradiance);
         * its depth stays z_r. The light near the terminator so reaches
         * the shade past it, as the path tracer shows (docs/quality.md,
         * "The light's entry, moved along its ray"). */
        if (!r->d.irradiance && ei[1] > 0) {
            float ndl = dot3(n, r->light);
            float direct = ei[1] - r->d.scene.ambient - (r->ind ? r->ind[3 * i + 1] : 0.0f);
            if (ndl > 0 && direct > 0) {
                float d = (float)(direct / ei[1] / (r->view.eta * r->dp.sigma_t[1]));
                for (int k = 0; k < 3; k++) p->p[k] -= (r->light[k] - n[k] * ndl) * d;
            }
        }
        if (carries(&r->d)) carry_across(r, pw, n, p, &r->pts[((irr_ctx *)ctx)->n + i]);
    }
}

static uint32_t exitance(const jd_ref *r, const float x[3], const float n[3], const float e[3], float out[3]);

/* The radiance leaving a point whose exitance is mo (n its normal)
 * towards a direction at cosine cosv, pi times, so 1 is a Lambertian
 * surface's. A half-space lit uniformly gives its light back by
 * Chandrasekhar's law of diffuse reflection, brighter towards grazing than
 * Lambertian where the light also grazes; light that diffused from far
 * leaves by the law of darkening, dimmer at grazing (jd_halfspace_exit). So
 * of mo, the part that the point's own light would give on a half-space
 * (loc: the beam's, then the diffuse light's, from hit_exitance) leaves by
 * the first (diffuse light by the half-space's albedo at that cosine, by
 * reciprocity), the rest by the second. Index-matched this took the dipole
 * reference from 7-9% too bright where it is lit from the front to Cycles'
 * brightness (docs/quality.md). */
static void leaving_light(const jd_ref *r, const float mo[3], const float loc[6], const float n[3], float cosv,
                          float out[3])
{
    float mu = cosv < 0 ? 0 : cosv > 1 ? 1 : cosv, mu0 = dot3(n, r->light);
    mu0 = mu0 < 0 ? 0 : mu0 > 1 ? 1 : mu0;
    /* Bilinear in the beam's table: the viewer's cosine by row, the light's by column. */
    const int w = JD_BEAM_STEPS + 1;
    float x = mu * JD_BEAM_STEPS, y = mu0 * JD_BEAM_STEPS;
    int i = x >= JD_BEAM_STEPS ? JD_BEAM_STEPS - 1 : (int)x, j = y >= JD_BEAM_STEPS ? JD_BEAM_STEPS - 1 : (int)y;
    float fx = x - (float)i, fy = y - (float)j;
    for (int k = 0; k < 3; k++) {
        const float *b = r->exit_beam[k];
        float gb = (1 - fx) * ((1 - fy) * b[i * w + j] + fy * b[i * w + j + 1]) +
                   fx * ((1 - fy) * b[(i + 1) * w + j] + fy * b[(i + 1) * w + j + 1]);
        float ld = loc[k], la = loc[3 + k], local = ld + la, m = mo[k] > 0 ? mo[k] : 0.0f;
        /* Less than the half-space would give (a thin part, a shadow's
         * edge): all of it is local light. */
        if (local > m) {
            float sc = m / local;
            ld *= sc, la *= sc, local = m;
        }
        out[k] = ld * gb + la * lerp_table(r->beam_scale[k], mu) + (m - local) * lerp_table(r->exit_deep[k], mu);
    }
}

/* The light scattered once on its way through the medium to the camera
 * (ref_single.h), added to what leaves the point seen, less what a
 * half-space lit as that point would scatter once: the local exit law
 * (leaving_light) already gives a half-space's whole reflection, first
 * order included, wherever it holds the light's own beam (loc's first
 * three: the point lit, its shadow ray already cast by hit_exitance); in
 * the proportion leaving_light kept of it. A model's colour scales it as
 * the point's diffused light (at entry and exit both: where the light
 * entered is a ray's length away, not looked up). */
static void add_single(const jd_ref *r, const jd_hit *hit, const float p[3], const float n[3], const float ng[3],
                       const float dir[3], const float mo[3], const float loc[6], uint32_t seed, float lo[3])
{
    float e = r->d.scene.light_intensity, s1[3], fo[3] = {1, 1, 1};
    if (dot3(dir, ng) >= 0) return; /* the inside of a face (an open mesh's): no medium entered here */
    /* No way out behind the point (an open mesh): the half-space's own
     * single scattering, in lo already, stands. */
    if (jd_single_scatter(&r->single, p, ng, dir, r->light, e, seed, s1) < 0) return;
    if (r->d.mesh->colors) albedo_factor(r, hit->tri, hit->u, hit->v, fo);
    float mu0 = dot3(n, r->light), mu = -dot3(n, dir);
    for (int k = 0; k < 3; k++) {
        float local = loc[k] + loc[3 + k], m = mo[k] > 0 ? mo[k] : 0.0f, keep = local > m ? m / local : 1.0f;
        float own = loc[k] > 0 ? keep * jd_single_halfspace(e, (float)r->dp.alpha[k], mu0, mu) : 0.0f;
        lo[k] = fmaxf(lo[k] + (s1[k] - own) * fo[k] * fo[k], 0.0f);
    }
}

/* The surface point a ray hit (p, its normal n and geometric normal ng)
 * and the light leaving it, Mo in its colour where the model has colours
 * (no Fresnel: the caller's direction decides it; loc gets what
 * leaving_light needs of the light entering there). Returns the kernel
 * evaluations it took. */
static uint32_t hit_exitance(const jd_ref *r, const jd_hit *hit, float p[3], float n[3], float ng[3], float mo[3],
                             float loc[6])
{
    float xm[3], ev[3], fo[3] = {1, 1, 1};
    surface_at(r, hit->tri, hit->u, hit->v, p, n, ng);
    irradiance(r, p, n, ng, ev);
    for (int k = 0; k < 3; k++) xm[k] = p[k] * r->mm_per_world;
    uint32_t evals = exitance(r, xm, n, ev, mo);
    if (r->d.mesh->colors) {
        albedo_factor(r, hit->tri, hit->u, hit->v, fo);
        for (int k = 0; k < 3; k++) mo[k] *= fo[k];
    }
    /* What a half-space lit as this point is would give out: the light's
     * beam and the diffuse rest (a caller's own irradiance is taken for
     * diffuse light), through the colour at entry and exit. */
    float amb = r->d.irradiance ? 0.0f : r->d.scene.ambient;
    for (int k = 0; k < 3; k++) {
        float rd = (float)r->dp.rd_total[k] * fo[k] * fo[k], a = r->d.irradiance ? ev[k] : amb;
        loc[k] = fmaxf(ev[k] - a, 0.0f) * rd;
        loc[3 + k] = fmaxf(a, 0.0f) * rd;
    }
    return evals;
}

/* The samples' irradiance (irr_chunk), the carried points packed behind
 * the samples, and the octrees over both, made anew. */
static jd_result light_samples(jd_ref *r, uint32_t n, float error, int progress, jd_error *err)
{
    irr_ctx ic = {r, n};
    double t0 = jd_clock_ms();
    par_run(r->st.threads, n, 2048, irr_chunk, &ic, "irradiance", progress);
    if (r->d.volume) {
        double t1 = jd_clock_ms();
        r->st.irradiance_ms += t1 - t0;
        jd_result res = jd_volume_solve(&r->vol, &r->vd, r->pts, r->pt_n, n, err);
        r->st.tree_ms += jd_clock_ms() - t1;
        r->st.volume_cells = r->vol.num_inside;
        r->st.volume_mm = r->vol.h;
        r->st.volume_iterations = r->vol.iterations;
        r->st.volume_residual = r->vol.residual;
        r->st.volume_lost = r->vol.lost;
        return res;
    }
    if (carries(&r->d)) {
        uint32_t all = n;
        for (uint32_t i = n; i < 2 * n; i++)
            if (r->pts[i].thick > 0) r->pts[all++] = r->pts[i];
        r->st.carried = all - n;
    }
    double t1 = jd_clock_ms();
    r->st.irradiance_ms += t1 - t0;
    jd_diffusion_free(&r->diff);
    jd_diffusion_free(&r->carry);
    jd_result res = jd_diffusion_build(&r->diff, r->pts, n, &r->dp, (float)r->st.window_mm, error, 0, err);
    /* The carried light's profile is as wide as the part is thick and has
     * no peak: a node may stand for its points at 4 times the bound (bunny,
     * 256x256, skin1 back-lit: 0.0003 RMSE from the same bound, pixels
     * 6.1 s -> 3.6 s). */
    if (!res && r->st.carried)
        res = jd_diffusion_build(&r->carry, r->pts + n, r->st.carried, &r->dp, (float)r->st.window_mm, 4.0f * error, 1,
                                 err);
    r->st.tree_ms += jd_clock_ms() - t1;
    return res;
}

/* The light the object's own surface sends each sample (inter-reflection):
 * JD_BOUNCE_RAYS rays over its outer hemisphere, cosine-distributed (a
 * spiral turned by a hash of the sample), each taking the exitance where it
 * meets the object again as the camera would see it there (the octrees as
 * they stand: each round adds one more bounce) and entering as the light
 * does, through the boundary at its angle. Air, not the medium, between:
 * the light leaves one part and enters another, as in a path tracer; the
 * dipole's straight distances never see it. */
enum { JD_BOUNCE_RAYS = 8 };
typedef struct bounce_ctx { jd_ref *r; const jd_ref_point *placed; } bounce_ctx;
static void bounce_chunk(void *ctx, long b, long e, uint64_t *evals)
{
    bounce_ctx *c = ctx;
    jd_ref *r = c->r;
    for (long i = b; i < e; i++) {
        const float *p = c->placed[i].p, *n = r->pt_n + 6 * i, *ng = r->pt_n + 6 * i + 3;
        float t[3], bt[3];
        jd_hemisphere_frame(n, t, bt);
        /* Leave on the outer side of the true surface. */
        float side = dot3(ng, n) >= 0 ? 1.0f : -1.0f, o[3], acc[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++) o[k] = p[k] + side * r->eps * ng[k];
        float turn = (float)((uint32_t)i * 2654435761u) * (1.0f / 4294967296.0f);
        for (int s = 0; s < JD_BOUNCE_RAYS; s++) {
            float d[3], cz = jd_cosine_ray(n, t, bt, s, JD_BOUNCE_RAYS, turn, d);
            jd_hit hit;
            if (!jd_bvh_intersect(&r->bvh, o, d, 0.0f, 1e30f, &hit)) continue;
            float q[3], nq[3], ngq[3], mo[3], loc[6], lo[3];
            *evals += hit_exitance(r, &hit, q, nq, ngq, mo, loc);
            float cq = -dot3(d, nq);
            if (cq <= 0) continue; /* the inside of a face: an open mesh's, or normals that disagree */
            /* Out of the medium there (as pixel_ray sees it) and into it here. */
            leaving_light(r, mo, loc, nq, cq, lo);
            float f = lerp_table(r->entry_t, cz);
            for (int k = 0; k < 3; k++) acc[k] += lo[k] * f;
        }
        /* Read by the next round's irr_chunk only: the octrees queried
         * here hold this round's light already. */
        for (int k = 0; k < 3; k++) r->ind[3 * i + k] = acc[k] / JD_BOUNCE_RAYS;
    }
}

/* The samples lit from r->light, then the light between parts (desc.bounces
 * rounds), then the octrees: from the samples as placed, so that lighting
 * again from another direction gives what a new jd_ref does. */
static jd_result light_all(jd_ref *r, jd_error *err)
{
    uint32_t n = r->n;
    memcpy(r->pts, r->placed, sizeof *r->placed * n);
    if (r->ind) memset(r->ind, 0, 3 * (size_t)n * sizeof *r->ind);
    r->st.irradiance_ms = r->st.tree_ms = r->st.bounce_ms = 0;
    float error = r->d.error > 0 ? r->d.error : 0.01f;
    jd_result res;
    for (int round = 0;; round++) {
        res = light_samples(r, n, error, r->d.progress, err);
        if (res || round >= r->d.bounces) break;
        double t2 = jd_clock_ms();
        bounce_ctx bc = {r, r->placed};
        par_run(r->st.threads, n, 512, bounce_chunk, &bc, "light between parts", r->d.progress);
        memcpy(r->pts, r->placed, sizeof *r->placed * n);
        r->st.bounce_ms += jd_clock_ms() - t2;
    }
    return res;
}

jd_result jd_ref_relight(jd_ref *r, float light_azimuth, jd_ref_stats *stats, jd_error *err)
{
    if (r->d.volume)
        return jd_fail(err, JD_ERR_ARG, "the volume (--volume) is solved for one light: no sequence of lights");
    r->d.scene.light_azimuth = light_azimuth;
    jd_scene_view_of(&r->d.scene, r->d.mesh, (float)r->d.width / (float)r->d.height, &r->view);
    jd_vec3 L = r->view.light_dir;
    r->light[0] = L.x; r->light[1] = L.y; r->light[2] = L.z;
    jd_result res = light_all(r, err);
    if (!res && stats) *stats = r->st;
    return res;
}

jd_result jd_ref_create(const jd_ref_desc *desc, jd_ref **out, jd_ref_stats *stats, jd_error *err)
{
    double t0 = jd_clock_ms();
    *out = NULL;
    const jd_mesh *m = desc->mesh;
    if (!m || m->num_indices < 3) return jd_fail(err, JD_ERR_ARG, "the mesh has no triangles");
    jd_ref *r = calloc(1, sizeof *r);
    if (!r) return jd_fail(err, JD_ERR_BUDGET, "out of memory");
    r->d = *desc;
    jd_scene *s = &r->d.scene;
    r->num_tris = m->num_indices / 3;
    r->pos = malloc(sizeof(float) * 3 * m->num_vertices);
    r->nrm = malloc(sizeof(float) * 3 * m->num_vertices);
    r->tri = malloc(sizeof(uint32_t) * 3 * (size_t)r->num_tris);
    if (!r->pos || !r->nrm || !r->tri) { jd_ref_destroy(r); return jd_fail(err, JD_ERR_BUDGET, "out of memory for the mesh"); }

    /* jade's world, camera, light and Fresnel: the renderer's own. */
    jd_scene_view_of(s, m, (float)desc->width / (float)desc->height, &r->view);
    jd_vec3 c = r->view.centre;
    float radius = r->view.radius;
    for (uint32_t i = 0; i < m->num_vertices; i++) {
        r->pos[3 * i] = (m->positions[3 * i] - c.x) / radius;
        r->pos[3 * i + 1] = (m->positions[3 * i + 1] - c.y) / radius;
        r->pos[3 * i + 2] = (m->positions[3 * i + 2] - c.z) / radius;
        memcpy(r->nrm + 3 * i, m->normals + 3 * i, 3 * sizeof(float));
    }
    for (uint32_t i = 0; i < 3 * r->num_tris; i++) r->tri[i] = jd_mesh_index(m, i);
    /* Light enters through the outside: turn normals that point in (a mesh
     * wound clockwise) around. For a closed surface the integral of x.n is
     * three times the volume, positive when n points out; an open one (a
     * floor, a sheet) has no inside, and its normals are taken as they come,
     * as the renderer takes them. */
    if (mesh_is_closed(r)) {
        double flux = 0;
        for (uint32_t t = 0; t < r->num_tris; t++) {
            const float *a, *b, *cc;
            tri_vertices(r, t, &a, &b, &cc);
            double area = jd_triangle_area(a, b, cc);
            for (int v = 0; v < 3; v++) {
                const float *nv = r->nrm + 3 * (size_t)r->tri[3 * t + v];
                flux += area * (a[0] + b[0] + cc[0]) / 3 * nv[0] + area * (a[1] + b[1] + cc[1]) / 3 * nv[1] +
                        area * (a[2] + b[2] + cc[2]) / 3 * nv[2];
            }
        }
        if (flux < 0)
            for (uint32_t i = 0; i < 3 * m->num_vertices; i++) r->nrm[i] = -r->nrm[i];
    }
    r->mm_per_world = r->view.mm_per_world;
    r->eps = 1e-4f;
    jd_vec3 L = r->view.light_dir;
    r->light[0] = L.x; r->light[1] = L.y; r->light[2] = L.z;
    jd_dipole_init(&r->dp, s->sigma_s, s->sigma_a, r->view.eta, s->density > 0 ? s->density : 1.0f);
    if (desc->single_scatter) {
        /* Traced straight from the light to the camera: through a smooth
         * dielectric that path is a caustic (it must refract towards one
         * direction at both ends), which rays from the camera do not find. */
        if (r->view.eta != 1.0f) {
            double eta = r->view.eta;
            jd_ref_destroy(r);
            return jd_fail(err, JD_ERR_ARG, "single scattering is traced through an index-matched boundary: it needs eta 1, not %g",
                           eta);
        }
        r->single = (jd_single){.bvh = &r->bvh, .nrm = r->nrm, .mm_per_world = r->view.mm_per_world};
        for (int k = 0; k < 3; k++) {
            r->single.sigma_t[k] = r->dp.sigma_t[k];
            r->single.sigma_s[k] = r->dp.alpha[k] * r->dp.sigma_t[k];
        }
    }
    for (int c = 0; c < 3; c++) {
        double diffuse = 0, beam[JD_BEAM_STEPS + 1];
        if (jd_halfspace_albedo_beam(r->dp.alpha[c], r->view.eta, JD_BEAM_STEPS + 1, beam, &diffuse)) {
            jd_ref_destroy(r);
            return jd_fail(err, JD_ERR_BUDGET, "out of memory for the half-space albedo's 400 x 400 system");
        }
        for (int k = 0; k <= JD_BEAM_STEPS; k++) r->beam_scale[c][k] = diffuse > 0 ? (float)(beam[k] / diffuse) : 1.0f;
        double deep[JD_BEAM_STEPS + 1], *bt = malloc(sizeof(double) * (JD_BEAM_STEPS + 1) * (JD_BEAM_STEPS + 1));
        if (!bt || jd_halfspace_exit(r->dp.alpha[c], r->view.eta, JD_BEAM_STEPS + 1, deep, bt)) {
            free(bt);
            jd_ref_destroy(r);
            return jd_fail(err, JD_ERR_BUDGET, "out of memory for the half-space's exit laws (a 400 x 400 system)");
        }
        for (int k = 0; k <= JD_BEAM_STEPS; k++) r->exit_deep[c][k] = (float)deep[k];
        for (int k = 0; k < (JD_BEAM_STEPS + 1) * (JD_BEAM_STEPS + 1); k++) r->exit_beam[c][k] = (float)bt[k];
        free(bt);
    }
    /* The true (unpolarised) transmittance into the medium, over its
     * cosine-weighted mean: jade's convention that a material's albedo is of
     * the diffuse light falling on it. Index-matched it is 1 everywhere. */
    double tmean = jd_fresnel_mean(r->view.eta);
    for (int k = 0; k <= JD_BEAM_STEPS; k++)
        r->entry_t[k] = (float)((1.0 - jd_fresnel_dielectric((double)k / JD_BEAM_STEPS, 1.0, r->view.eta)) / tmean);
    r->st.mm_per_world = r->mm_per_world;
    r->st.threads = desc->threads > 0 ? desc->threads : core_count();

    jd_result res = jd_bvh_build(&r->bvh, r->pos, r->tri, r->num_tris, err);
    if (res) { jd_ref_destroy(r); return res; }
    if (desc->volume) {
        r->vd = (jd_volume_desc){.bvh = &r->bvh, .mm_per_world = r->mm_per_world, .dp = &r->dp,
                                 .cell_mm = desc->volume_mm};
        res = jd_volume_init(&r->vol, &r->vd, err);
        if (res) { jd_ref_destroy(r); return res; }
    }

    /* Samples uniform by area, spread evenly (ref_samples.h). */
    double total = 0;
    for (uint32_t t = 0; t < r->num_tris; t++) {
        const float *a, *b, *cc;
        tri_vertices(r, t, &a, &b, &cc);
        total += jd_triangle_area(a, b, cc);
    }
    if (!(total > 0)) { jd_ref_destroy(r); return jd_fail(err, JD_ERR_ARG, "the mesh has no area"); }
    double mm2 = (double)r->mm_per_world * r->mm_per_world;
    r->st.surface_mm2 = total * mm2;
    uint32_t n = desc->samples;
    if (!n && desc->volume) {
        /* Four a cell face: fewer leave the cells under the surface a
         * sample's graininess (fandisk, front-lit: blotches a few cells
         * wide at one a face, gone at four). */
        double sp = fmin(0.3, 0.5 * r->vol.h), want = r->st.surface_mm2 / (sp * sp);
        n = (uint32_t)(want < 20000 ? 20000 : want > 4000000 ? 4000000 : want);
    } else if (!n) {
        double want = r->st.surface_mm2 / (0.3 * 0.3);
        n = (uint32_t)(want < 20000 ? 20000 : want > 400000 ? 400000 : want);
    }
    jd_surface_point *sp = NULL;
    res = jd_surface_samples(r->pos, r->tri, r->num_tris, n, desc->seed, &sp, &n, err);
    if (res) { jd_ref_destroy(r); return res; }
    /* Room for each sample's light carried across a thin part. */
    r->pts = malloc(sizeof *r->pts * (n ? n : 1) * (carries(desc) ? 2 : 1));
    r->pt_n = malloc(sizeof(float) * 6 * (n ? n : 1));
    if (!r->pts || !r->pt_n) {
        free(sp);
        jd_ref_destroy(r);
        return jd_fail(err, JD_ERR_BUDGET, "out of memory for %u irradiance samples", n);
    }
    double area_mm2 = total / (n ? n : 1) * mm2;
    if (m->colors && !(r->pt_alb = malloc(sizeof(float) * 3 * (n ? n : 1)))) {
        free(sp);
        jd_ref_destroy(r);
        return jd_fail(err, JD_ERR_BUDGET, "out of memory for %u irradiance samples", n);
    }
    for (uint32_t k = 0; k < n; k++) {
        float p[3], nn[3], ng[3];
        surface_at(r, sp[k].tri, sp[k].u, sp[k].v, p, nn, ng);
        memcpy(r->pts[k].p, p, sizeof p);
        memcpy(r->pt_n + 6 * k, nn, sizeof nn);
        memcpy(r->pt_n + 6 * k + 3, ng, sizeof ng);
        r->pts[k].area = (float)area_mm2;
        r->pts[k].thick = 0; /* a sample of the surface */
        if (r->pt_alb) albedo_factor(r, sp[k].tri, sp[k].u, sp[k].v, r->pt_alb + 3 * (size_t)k);
    }
    free(sp);
    r->st.samples = n;
    r->st.spacing_mm = sqrt(area_mm2);
    r->st.window_mm = desc->window_mm > 0 ? desc->window_mm : fmax(2.5, 3.0 * r->st.spacing_mm);
    r->st.setup_ms = jd_clock_ms() - t0;

    r->n = n;
    r->placed = malloc(sizeof *r->placed * n);
    if (!r->placed) {
        jd_ref_destroy(r);
        return jd_fail(err, JD_ERR_BUDGET, "out of memory for a copy of %u samples as placed", n);
    }
    if (desc->bounces > 0 && !(r->ind = calloc(3 * (size_t)n, sizeof *r->ind))) {
        jd_ref_destroy(r);
        return jd_fail(err, JD_ERR_BUDGET, "out of memory for the light of %u samples on each other", n);
    }
    memcpy(r->placed, r->pts, sizeof *r->placed * n);
    res = light_all(r, err);
    if (res) { jd_ref_destroy(r); return res; }
    if (stats) *stats = r->st;
    *out = r;
    return JD_OK;
}

/* Mo at x (mm, outward normal n) where the irradiance is e: the samples'
 * light and what thin parts carried there, or the volume's solve. */
static uint32_t exitance(const jd_ref *r, const float x[3], const float n[3], const float e[3], float out[3])
{
    if (r->d.volume) {
        /* The solve's light is diffusion's; the exact albedo's excess over
         * it leaves at the point it entered (ref_diffusion.c). */
        jd_volume_exitance(&r->vol, x, n, out);
        for (int c = 0; c < 3; c++) out[c] += (float)((1.0 - jd_ref_diffusion_share(&r->dp, c)) * r->dp.rd_total[c]) * e[c];
        return 1;
    }
    uint32_t evals = jd_diffusion_exitance(&r->diff, x, e, out);
    if (r->carry.num_nodes) {
        float t[3];
        evals += jd_diffusion_exitance(&r->carry, x, e, t);
        for (int c = 0; c < 3; c++) out[c] += t[c];
    }
    return evals;
}

void jd_ref_destroy(jd_ref *r)
{
    if (!r) return;
    jd_diffusion_free(&r->diff);
    jd_diffusion_free(&r->carry);
    jd_volume_free(&r->vol);
    jd_bvh_free(&r->bvh);
    free(r->pos); free(r->nrm); free(r->tri); free(r->pts); free(r->pt_n); free(r->pt_alb); free(r->ind);
    free(r->placed);
    free(r);
}

void jd_ref_exitance(const jd_ref *r, const float p[3], const float n[3], float out[3])
{
    float e[3], ng[3] = {n[0], n[1], n[2]}, x[3];
    irradiance(r, p, n, ng, e);
    for (int k = 0; k < 3; k++) x[k] = p[k] * r->mm_per_world;
    exitance(r, x, n, e, out);
}

/* ---- the picture -------------------------------------------------------- */

typedef struct px_ctx {
    jd_ref *r;
    float *linear;
    uint8_t *mask;
    float eye[3], fwd[3], right[3], up[3];
    float tan_half, aspect;
    float bg[3];  /* the background, linear (its clear colour is sqrt(background): past the shoulder) */
} px_ctx;

/* The camera's ray through picture point (fx, fy), in pixels from the top left. */
static void ray_dir(const px_ctx *c, float fx, float fy, float dir[3])
{
    float sx = (2.0f * fx / c->r->d.width - 1.0f) * c->tan_half * c->aspect;
    float sy = (1.0f - 2.0f * fy / c->r->d.height) * c->tan_half;
    for (int k = 0; k < 3; k++) dir[k] = c->fwd[k] + sx * c->right[k] + sy * c->up[k];
    normalize3(dir);
}

/* The linear colour along the ray through picture point (fx, fy): 1 where
 * it hits the object, 0 (the background) where not. */
static int pixel_ray(px_ctx *c, float fx, float fy, float o[3], uint64_t *evals)
{
    jd_ref *r = c->r;
    const jd_scene *s = &r->d.scene;
    float shin = r->view.shininess, expo = r->view.exposure;
    float dir[3];
    ray_dir(c, fx, fy, dir);
    jd_hit hit;
    if (!jd_bvh_intersect(&r->bvh, c->eye, dir, 0.0f, 1e30f, &hit)) {
        memcpy(o, c->bg, sizeof c->bg);
        return 0;
    }
    float p[3], n[3], ng[3], mo[3], loc[6];
    *evals += hit_exitance(r, &hit, p, n, ng, mo, loc);
    /* Seen from the camera's side, as jade's shader does. */
    float v[3] = {-dir[0], -dir[1], -dir[2]}, nv[3];
    float sgn = dot3(n, v) < 0 ? -1.0f : 1.0f;
    for (int k = 0; k < 3; k++) nv[k] = sgn * n[k];
    float lo[3];
    leaving_light(r, mo, loc, n, dot3(nv, v), lo); /* n: the normal mo and loc are of */
    float ndl = fmaxf(dot3(nv, r->light), 0.0f), hv[3];
    for (int k = 0; k < 3; k++) hv[k] = r->light[k] + v[k];
    normalize3(hv);
    /* The highlight is the light's mirror image: none in shadow. */
    float spec = ndl > 0 && light_visible(r, p, ng)
                     ? s->specular * powf(fmaxf(dot3(nv, hv), 0.0f), shin) * s->light_intensity
                     : 0.0f;
    if (r->d.single_scatter) add_single(r, &hit, p, n, ng, dir, mo, loc, (uint32_t)(fx * 7919.0f) ^ (uint32_t)(fy * 104729.0f), lo);
    for (int k = 0; k < 3; k++) o[k] = (lo[k] + spec) * expo;
    return 1;
}

static int center_hit(px_ctx *c, int x, int y)
{
    float dir[3];
    ray_dir(c, x + 0.5f, y + 0.5f, dir);
    jd_hit hit;
    return jd_bvh_intersect(&c->r->bvh, c->eye, dir, 0.0f, 1e30f, &hit);
}

static void px_rows(void *ctx, long b, long e, uint64_t *evals)
{
    px_ctx *c = ctx;
    jd_ref *r = c->r;
    int w = r->d.width;
    for (long y = b; y < e; y++) {
        for (int x = 0; x < w; x++) {
            float *o = c->linear + 3 * ((size_t)y * w + x);
            int ns = r->d.pixel_samples > 1 ? r->d.pixel_samples : 1, hits = 0;
            float acc[3] = {0, 0, 0};
            for (int sy_i = 0; sy_i < ns; sy_i++)
                for (int sx_i = 0; sx_i < ns; sx_i++) {
                    float ox = (sx_i + 0.5f) / ns, oy = (sy_i + 0.5f) / ns, px[3];
                    if (pixel_ray(c, x + ox, y + oy, px, evals)) hits++;
                    for (int k = 0; k < 3; k++) acc[k] += px[k];
                }
            for (int k = 0; k < 3; k++) o[k] = acc[k] / (float)(ns * ns);
            /* The object's pixels: where its centre ray hits, as with one ray. */
            if (c->mask) c->mask[(size_t)y * w + x] = ns == 1 ? (hits ? 255 : 0) : center_hit(c, x, y) ? 255 : 0;
        }
    }
}

jd_result jd_ref_render(jd_ref *r, float *linear, uint8_t *mask, jd_ref_stats *stats, jd_error *err)
{
    int w = r->d.width, h = r->d.height;
    if (w < 1 || h < 1) return jd_fail(err, JD_ERR_ARG, "image size %dx%d", w, h);
    px_ctx c = {.r = r, .linear = linear, .mask = mask};
    /* jd_m4_look_at and jd_m4_perspective, as rays: the view matrix's rows
     * are the camera's right, up and backward axes (its own choice of up
     * where the camera looks almost straight down, which a copy missed:
     * at --pitch 89 the reference came out turned by 90 degrees). */
    jd_vec3 eye = r->view.eye;
    jd_mat4 view = jd_m4_look_at(eye, jd_v3(0, 0, 0), jd_v3(0, 1, 0));
    jd_vec3 rt = jd_v3(view.m[0], view.m[4], view.m[8]);
    jd_vec3 up = jd_v3(view.m[1], view.m[5], view.m[9]);
    jd_vec3 f = jd_v3(-view.m[2], -view.m[6], -view.m[10]);
    c.eye[0] = eye.x; c.eye[1] = eye.y; c.eye[2] = eye.z;
    c.fwd[0] = f.x; c.fwd[1] = f.y; c.fwd[2] = f.z;
    c.right[0] = rt.x; c.right[1] = rt.y; c.right[2] = rt.z;
    c.up[0] = up.x; c.up[1] = up.y; c.up[2] = up.z;
    c.tan_half = tanf(r->view.fov_deg * 3.14159265f / 360.0f);
    c.aspect = (float)w / (float)h;
    for (int k = 0; k < 3; k++) c.bg[k] = jd_shoulder_inverse(r->d.scene.background[k]);
    double t0 = jd_clock_ms();
    uint64_t ev = par_run(r->st.threads, h, 1, px_rows, &c, "reference", r->d.progress);
    r->st.pixels_ms = jd_clock_ms() - t0;
    long obj = 0;
    if (mask)
        for (long i = 0; i < (long)w * h; i++) obj += mask[i] != 0;
    r->st.object_pixels = obj;
    r->st.evals_per_pixel = obj ? (double)ev / obj : 0;
    for (long i = 0; i < 3L * w * h; i++)
        if (!isfinite(linear[i]) || linear[i] < 0)
            return jd_fail(err, JD_ERR_ARG, "pixel %ld came out %g: the scene's numbers are out of range", i / 3,
                           (double)linear[i]);
    if (stats) *stats = r->st;
    return JD_OK;
}
