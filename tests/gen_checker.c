/* gen_checker OUT.gltf SHIFT: a thin box whose front face's texture
 * coordinates run over [0.875, 1) + SHIFT in both directions (128 of the
 * texture's 1024 texels, where a 16-bit float's steps are coarsest below
 * 1), the texture a checker of single texels, embedded: tests/textures.sh
 * checks that the loader moves coordinates by whole tiles. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

enum { SIDE = 1024 };

static void collect(void *ctx, void *data, int size)
{
    struct { unsigned char *p; size_t n; } *b = ctx;
    b->p = realloc(b->p, b->n + (size_t)size);
    memcpy(b->p + b->n, data, (size_t)size);
    b->n += (size_t)size;
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

int main(int argc, char **argv)
{
    if (argc != 3) { fprintf(stderr, "usage: gen_checker OUT.gltf SHIFT\n"); return 2; }
    float shift = (float)atof(argv[2]);
    unsigned char *tex = malloc(SIDE * SIDE * 3);
    for (int y = 0; y < SIDE; y++)
        for (int x = 0; x < SIDE; x++) {
            unsigned char *o = tex + 3 * (y * SIDE + x);
            int on = (x + y) & 1;
            o[0] = on ? 240 : 40;
            o[1] = on ? 200 : 60;
            o[2] = on ? 120 : 90;
        }
    struct { unsigned char *p; size_t n; } png = {0, 0};
    stbi_write_png_to_func(collect, &png, SIDE, SIDE, 3, tex, SIDE * 3);
    /* A thin box (so that it has a volume and an outside), its front face
     * textured; positions, normals, coordinates, then 16-bit indices. */
    float lo = 0.875f + shift, hi = 1.0f + shift - 1.0f / SIDE;
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
    FILE *f = fopen(argv[1], "w");
    if (!f) { perror(argv[1]); return 1; }
    fprintf(f,
            "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},\"indices\":3,"
            "\"material\":0}]}],\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
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
