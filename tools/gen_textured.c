/* jade's own textured test models (assets/textured/): a pebble, an egg
 * flattened on one side and thin at one end, with a veined colour texture;
 * written as a glTF with everything embedded, an OBJ with its MTL and PNG,
 * and a PLY with vertex colours. Run by tools/make_textured_assets.sh. With
 * --checker, the test model of tests/textures.sh (built by the tests); with
 * --quantized, the pebble as gltfpack and glTF-Transform write a glTF by
 * default (KHR_mesh_quantization: 16-bit positions placed by the node,
 * 8-bit normals, 16-bit coordinates that KHR_texture_transform maps back;
 * here turned a quarter round, so that the transform's rotation is tested
 * too), for tests/textures.sh.
 *
 *   gen_textured OUTDIR
 *   gen_textured --checker OUT.gltf SHIFT
 *   gen_textured --quantized OUT.gltf */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

enum { SEG = 48, RING = 24, TEX = 128, CHECKER = 1024 };
#define NV ((SEG + 1) * (RING + 1))
#define NT (SEG * RING * 2)

static float pos[NV][3], nrm[NV][3], uv[NV][2];
static unsigned idx[NT][3];
static unsigned char tex[TEX * TEX * 3];

/* The surface: a sphere stretched into an egg, thin towards +x. */
static void point(float u, float v, float p[3])
{
    float th = u * 6.2831853f, ph = v * 3.14159265f;
    float x = -cosf(th) * sinf(ph), y = cosf(ph), z = sinf(th) * sinf(ph);
    float taper = 1.0f - 0.55f * (x + 1.0f) * 0.5f; /* thinner towards +x */
    p[0] = 1.0f * x;
    p[1] = 0.55f * y * taper;
    p[2] = 0.6f * z * taper;
}

static void build(void)
{
    for (int r = 0; r <= RING; r++)
        for (int s = 0; s <= SEG; s++) {
            int i = r * (SEG + 1) + s;
            float u = (float)s / SEG, v = (float)r / RING;
            point(u, v, pos[i]);
            uv[i][0] = u;
            uv[i][1] = v;
            /* The normal from the surface's own derivatives. */
            float a[3], b[3], c[3], d[3], e = 1e-3f;
            point(u + e, v, a);
            point(u - e, v, b);
            point(u, fminf(v + e, 1.0f), c);
            point(u, fmaxf(v - e, 0.0f), d);
            float du[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]}, dv[3] = {c[0] - d[0], c[1] - d[1], c[2] - d[2]};
            float n[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]};
            float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (r == 0 || r == RING || l < 1e-12f) {
                n[0] = 0; n[1] = r == 0 ? 1.0f : -1.0f; n[2] = 0; l = 1;
            }
            /* Outward: the egg is star-shaped about the origin. */
            if (n[0] * pos[i][0] + n[1] * pos[i][1] + n[2] * pos[i][2] < 0) l = -l;
            for (int k = 0; k < 3; k++) nrm[i][k] = n[k] / l;
        }
    int t = 0;
    for (int r = 0; r < RING; r++)
        for (int s = 0; s < SEG; s++) {
            unsigned a = r * (SEG + 1) + s, b = a + 1, c = a + SEG + 1, d = c + 1;
            /* Counter-clockwise seen from outside. */
            idx[t][0] = a; idx[t][1] = c; idx[t][2] = b; t++;
            idx[t][0] = b; idx[t][1] = c; idx[t][2] = d; t++;
        }
    /* Veins of a deep red through a warm white, and bands of green-grey:
     * colours far apart, so that a renderer that ignores the texture, or
     * mixes the channels, shows it. sRGB-encoded, as PNGs are. */
    for (int y = 0; y < TEX; y++)
        for (int x = 0; x < TEX; x++) {
            float u = (x + 0.5f) / TEX, v = (y + 0.5f) / TEX;
            float w = sinf(6.2831853f * (3.0f * u + 0.8f * sinf(6.2831853f * 2.0f * v)));
            float vein = expf(-12.0f * w * w);
            float band = 0.5f + 0.5f * sinf(6.2831853f * 4.0f * v);
            float base[3] = {0.93f, 0.88f, 0.80f}, red[3] = {0.55f, 0.08f, 0.06f}, green[3] = {0.55f, 0.68f, 0.58f};
            unsigned char *o = tex + 3 * (y * TEX + x);
            for (int k = 0; k < 3; k++) {
                float c = base[k] * (1 - 0.6f * band) + green[k] * 0.6f * band;
                c = c * (1 - vein) + red[k] * vein;
                o[k] = (unsigned char)(c * 255.0f + 0.5f);
            }
        }
}

/* The one primitive every model here has: its attributes, indices and
 * material by index. */
#define PRIMITIVE_JSON                                                                                              \
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},\"indices\":3," \
    "\"material\":0}]}],"

/* The pebble's box. */
static void box(float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = 1e9f;
        hi[k] = -1e9f;
    }
    for (int i = 0; i < NV; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], pos[i][k]);
            hi[k] = fmaxf(hi[k], pos[i][k]);
        }
}

static char *b64(const unsigned char *d, size_t n)
{
    static const char t[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char *o = malloc(n / 3 * 4 + 8), *p = o;
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = d[i] << 16 | (i + 1 < n ? d[i + 1] << 8 : 0) | (i + 2 < n ? d[i + 2] : 0);
        *p++ = t[v >> 18 & 63];
        *p++ = t[v >> 12 & 63];
        *p++ = i + 1 < n ? t[v >> 6 & 63] : '=';
        *p++ = i + 2 < n ? t[v & 63] : '=';
    }
    *p = 0;
    return o;
}

static void collect(void *ctx, void *data, int size)
{
    struct { unsigned char *p; size_t n; } *b = ctx;
    b->p = realloc(b->p, b->n + (size_t)size);
    memcpy(b->p + b->n, data, (size_t)size);
    b->n += (size_t)size;
}

static FILE *out(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) { perror(path); exit(1); }
    return f;
}

/* A thin box whose front face's texture coordinates run over [0.875, 1) +
 * shift in both directions (128 of the texture's 1024 texels, where a
 * 16-bit float's steps are coarsest below 1), the texture a checker of
 * single texels, embedded: tests/textures.sh checks that the loader moves
 * coordinates by whole tiles. */
static int checker(const char *out, float shift)
{
    unsigned char *tex = malloc(CHECKER * CHECKER * 3);
    for (int y = 0; y < CHECKER; y++)
        for (int x = 0; x < CHECKER; x++) {
            unsigned char *o = tex + 3 * (y * CHECKER + x);
            int on = (x + y) & 1;
            o[0] = on ? 240 : 40;
            o[1] = on ? 200 : 60;
            o[2] = on ? 120 : 90;
        }
    struct { unsigned char *p; size_t n; } png = {0, 0};
    stbi_write_png_to_func(collect, &png, CHECKER, CHECKER, 3, tex, CHECKER * 3);
    /* A thin box (so that it has a volume and an outside), its front face
     * textured; positions, normals, coordinates, then 16-bit indices. */
    float lo = 0.875f + shift, hi = 1.0f + shift - 1.0f / CHECKER;
    float v[8][8] = {
        {-1, -1, 0.05f, 0, 0, 1, lo, hi}, {1, -1, 0.05f, 0, 0, 1, hi, hi}, {1, 1, 0.05f, 0, 0, 1, hi, lo}, {-1, 1, 0.05f, 0, 0, 1, lo, lo},
        {-1, -1, -0.05f, 0, 0, -1, lo, hi}, {1, -1, -0.05f, 0, 0, -1, hi, hi}, {1, 1, -0.05f, 0, 0, -1, hi, lo}, {-1, 1, -0.05f, 0, 0, -1, lo, lo}};
    unsigned short idx[] = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1, 1, 5, 6, 1, 6, 2, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0};
    unsigned char buf[8 * 32 + sizeof idx];
    float pos[8][3], nrm[8][3], uv[8][2];
    for (int i = 0; i < 8; i++) {
        memcpy(pos[i], v[i], 12);
        memcpy(nrm[i], v[i] + 3, 12);
        memcpy(uv[i], v[i] + 6, 8);
    }
    memcpy(buf, pos, 96);
    memcpy(buf + 96, nrm, 96);
    memcpy(buf + 192, uv, 64);
    memcpy(buf + 256, idx, sizeof idx);
    char *bb = b64(buf, sizeof buf), *pb = b64(png.p, png.n);
    FILE *f = fopen(out, "w");
    if (!f) { perror(out); return 1; }
    fprintf(f,
            "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
            PRIMITIVE_JSON "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
            "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"data:image/png;base64,%s\"}],"
            "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteLength\":96},{\"buffer\":0,\"byteOffset\":96,\"byteLength\":96},"
            "{\"buffer\":0,\"byteOffset\":192,\"byteLength\":64},{\"buffer\":0,\"byteOffset\":256,\"byteLength\":%zu}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":8,\"type\":\"VEC3\",\"min\":[-1,-1,-0.05],"
            "\"max\":[1,1,0.05]},{\"bufferView\":1,\"componentType\":5126,\"count\":8,\"type\":\"VEC3\"},"
            "{\"bufferView\":2,\"componentType\":5126,\"count\":8,\"type\":\"VEC2\"},"
            "{\"bufferView\":3,\"componentType\":5123,\"count\":36,\"type\":\"SCALAR\"}]}\n",
            pb, sizeof buf, bb, sizeof idx);
    fclose(f);
    free(tex);
    free(png.p);
    free(bb);
    free(pb);
    return 0;
}

/* The pebble quantized: positions as unsigned 16-bit integers over the
 * mesh's box, which the node's scale (one for the three axes, as gltfpack
 * has it: a scale per axis would turn the normals, which stay the mesh's
 * own) and translation undo; normals as
 * normalized signed bytes (4-byte stride, as the extension requires);
 * texture coordinates (u, v) stored as (v, 1 - u) in normalized unsigned
 * 16 bits, which KHR_texture_transform's rotation of a quarter turn and
 * offset (1, 0) take back to (u, v). */
static int quantized(const char *outpath)
{
    build();
    struct { unsigned char *p; size_t n; } png = {0, 0};
    stbi_write_png_to_func(collect, &png, TEX, TEX, 3, tex, TEX * 3);
    float lo[3], hi[3];
    box(lo, hi);
    float ext = fmaxf(hi[0] - lo[0], fmaxf(hi[1] - lo[1], hi[2] - lo[2]));
    size_t bp = (size_t)NV * 8, bn = (size_t)NV * 4, bu = (size_t)NV * 4, bi = sizeof idx;
    unsigned char *buf = calloc(1, bp + bn + bu + bi);
    for (int i = 0; i < NV; i++) {
        unsigned short q[4] = {0, 0, 0, 0};
        for (int k = 0; k < 3; k++) q[k] = (unsigned short)lrintf((pos[i][k] - lo[k]) / ext * 65535.0f);
        memcpy(buf + 8 * (size_t)i, q, 8);
        signed char nb[4] = {0, 0, 0, 0};
        for (int k = 0; k < 3; k++) nb[k] = (signed char)lrintf(nrm[i][k] * 127.0f);
        memcpy(buf + bp + 4 * (size_t)i, nb, 4);
        unsigned short t[2] = {(unsigned short)lrintf(uv[i][1] * 65535.0f), (unsigned short)lrintf((1.0f - uv[i][0]) * 65535.0f)};
        memcpy(buf + bp + bn + 4 * (size_t)i, t, 4);
    }
    memcpy(buf + bp + bn + bu, idx, bi);
    char *b64buf = b64(buf, bp + bn + bu + bi), *b64png = b64(png.p, png.n);
    FILE *f = fopen(outpath, "w");
    if (!f) { perror(outpath); return 1; }
    fprintf(f,
            "{\"asset\":{\"version\":\"2.0\",\"generator\":\"jade tools/gen_textured.c --quantized\"},\"scene\":0,"
            "\"extensionsUsed\":[\"KHR_mesh_quantization\",\"KHR_texture_transform\"],"
            "\"extensionsRequired\":[\"KHR_mesh_quantization\",\"KHR_texture_transform\"],"
            "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"translation\":[%.9g,%.9g,%.9g],"
            "\"scale\":[%.9g,%.9g,%.9g]}],"
            PRIMITIVE_JSON
            "\"materials\":[{\"name\":\"veined\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0,"
            "\"extensions\":{\"KHR_texture_transform\":{\"offset\":[1,0],\"rotation\":1.5707963267948966}}},"
            "\"metallicFactor\":0}}],"
            "\"textures\":[{\"source\":0,\"sampler\":0}],\"samplers\":[{\"wrapS\":10497,\"wrapT\":10497}],"
            "\"images\":[{\"uri\":\"data:image/png;base64,%s\"}],"
            "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%zu,\"byteStride\":8},{\"buffer\":0,\"byteOffset\":%zu,"
            "\"byteLength\":%zu,\"byteStride\":4},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"byteStride\":4},"
            "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5123,\"count\":%d,\"type\":\"VEC3\",\"min\":[0,0,0],"
            "\"max\":[%d,%d,%d]},{\"bufferView\":1,\"componentType\":5120,\"normalized\":true,\"count\":%d,"
            "\"type\":\"VEC3\"},{\"bufferView\":2,\"componentType\":5123,\"normalized\":true,\"count\":%d,"
            "\"type\":\"VEC2\"},{\"bufferView\":3,\"componentType\":5125,\"count\":%d,\"type\":\"SCALAR\"}]}\n",
            lo[0], lo[1], lo[2], ext / 65535.0, ext / 65535.0, ext / 65535.0, b64png,
            bp + bn + bu + bi, b64buf, bp, bp, bn, bp + bn, bu, bp + bn + bu, bi, NV,
            (int)lrintf((hi[0] - lo[0]) / ext * 65535.0f), (int)lrintf((hi[1] - lo[1]) / ext * 65535.0f),
            (int)lrintf((hi[2] - lo[2]) / ext * 65535.0f), NV, NV, NT * 3);
    fclose(f);
    free(buf);
    free(b64buf);
    free(b64png);
    free(png.p);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 4 && !strcmp(argv[1], "--checker")) return checker(argv[2], (float)atof(argv[3]));
    if (argc == 3 && !strcmp(argv[1], "--quantized")) return quantized(argv[2]);
    if (argc != 2) {
        fprintf(stderr, "usage: gen_textured OUTDIR | --checker OUT.gltf SHIFT | --quantized OUT.gltf\n");
        return 2;
    }
    const char *dir = argv[1];
    build();
    struct { unsigned char *p; size_t n; } png = {0, 0};
    stbi_write_png_compression_level = 9;
    stbi_write_png_to_func(collect, &png, TEX, TEX, 3, tex, TEX * 3);
    FILE *f = out(dir, "pebble.png");
    fwrite(png.p, 1, png.n, f);
    fclose(f);

    /* glTF: one buffer (positions, normals, uvs, indices) and the PNG, as data: URIs. */
    size_t bp = sizeof pos, bn = sizeof nrm, bu = sizeof uv, bi = sizeof idx;
    unsigned char *buf = malloc(bp + bn + bu + bi);
    memcpy(buf, pos, bp);
    memcpy(buf + bp, nrm, bn);
    memcpy(buf + bp + bn, uv, bu);
    memcpy(buf + bp + bn + bu, idx, bi);
    char *b64buf = b64(buf, bp + bn + bu + bi), *b64png = b64(png.p, png.n);
    float lo[3], hi[3];
    box(lo, hi);
    f = out(dir, "pebble.gltf");
    fprintf(f,
            "{\"asset\":{\"version\":\"2.0\",\"generator\":\"jade tools/gen_textured.c\"},\"scene\":0,"
            "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
            PRIMITIVE_JSON
            "\"materials\":[{\"name\":\"veined\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},"
            "\"metallicFactor\":0}}],"
            "\"textures\":[{\"source\":0,\"sampler\":0}],\"samplers\":[{\"wrapS\":10497,\"wrapT\":10497}],"
            "\"images\":[{\"uri\":\"data:image/png;base64,%s\"}],"
            "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,"
            "\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,"
            "\"byteLength\":%zu}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\",\"min\":[%g,%g,%g],"
            "\"max\":[%g,%g,%g]},{\"bufferView\":1,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
            "{\"bufferView\":2,\"componentType\":5126,\"count\":%d,\"type\":\"VEC2\"},"
            "{\"bufferView\":3,\"componentType\":5125,\"count\":%d,\"type\":\"SCALAR\"}]}\n",
            b64png, bp + bn + bu + bi, b64buf, bp, bp, bn, bp + bn, bu, bp + bn + bu, bi, NV, lo[0], lo[1], lo[2], hi[0],
            hi[1], hi[2], NV, NV, NT * 3);
    fclose(f);

    /* OBJ + MTL: v counts from the bottom of the picture in OBJ. */
    f = out(dir, "pebble.mtl");
    fprintf(f, "# jade tools/gen_textured.c\nnewmtl veined\nKd 0.8 0.8 0.8\nmap_Kd pebble.png\n");
    fclose(f);
    f = out(dir, "pebble.obj");
    fprintf(f, "# jade tools/gen_textured.c\nmtllib pebble.mtl\n");
    for (int i = 0; i < NV; i++) fprintf(f, "v %.6f %.6f %.6f\n", pos[i][0], pos[i][1], pos[i][2]);
    for (int i = 0; i < NV; i++) fprintf(f, "vt %.6f %.6f\n", uv[i][0], 1.0f - uv[i][1]);
    for (int i = 0; i < NV; i++) fprintf(f, "vn %.6f %.6f %.6f\n", nrm[i][0], nrm[i][1], nrm[i][2]);
    fprintf(f, "usemtl veined\n");
    for (int t = 0; t < NT; t++)
        fprintf(f, "f %u/%u/%u %u/%u/%u %u/%u/%u\n", idx[t][0] + 1, idx[t][0] + 1, idx[t][0] + 1, idx[t][1] + 1,
                idx[t][1] + 1, idx[t][1] + 1, idx[t][2] + 1, idx[t][2] + 1, idx[t][2] + 1);
    fclose(f);

    /* PLY: the texture's colour at each vertex, sRGB bytes as scanners write them. */
    f = out(dir, "pebble_colours.ply");
    fprintf(f, "ply\nformat ascii 1.0\ncomment jade tools/gen_textured.c\nelement vertex %d\nproperty float x\n"
               "property float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
               "element face %d\nproperty list uchar int vertex_indices\nend_header\n", NV, NT);
    for (int i = 0; i < NV; i++) {
        int x = (int)(uv[i][0] * TEX), y = (int)(uv[i][1] * TEX);
        x = x >= TEX ? TEX - 1 : x;
        y = y >= TEX ? TEX - 1 : y;
        const unsigned char *c = tex + 3 * (y * TEX + x);
        fprintf(f, "%.6f %.6f %.6f %u %u %u\n", pos[i][0], pos[i][1], pos[i][2], c[0], c[1], c[2]);
    }
    for (int t = 0; t < NT; t++) fprintf(f, "3 %u %u %u\n", idx[t][0], idx[t][1], idx[t][2]);
    fclose(f);
    free(buf);
    free(b64buf);
    free(b64png);
    free(png.p);
    return 0;
}
