// Fixed-point packing of one value in [0,1] into RGBA8 bytes. Every factor is
// 255 or less, so nothing overflows fp16 (largest finite 65504) on
// mediump-only GPUs. JD_PACK_HIGHP: three bytes (~24 bits); otherwise two
// bytes, about what fp16 arithmetic can carry anyway (~11-12 bits).
vec4 jd_pack(float v)
{
    v = clamp(v, 0.0, 1.0);
    float a = v * 255.0;
    float b0 = floor(a);
    float r1 = a - b0;
#if JD_PACK_HIGHP
    float c = r1 * 255.0;
    float b1 = floor(c);
    return vec4(b0 / 255.0, b1 / 255.0, c - b1, 1.0);
#else
    return vec4(b0 / 255.0, r1, 0.0, 1.0);
#endif
}

// Texture units do not all turn a byte b into exactly b/255 (llvmpipe is off
// by a few parts in 1e5, which a reduction turns into a bias): recover the
// bytes first, then combine them.
float jd_unpack(vec4 p)
{
    vec3 b = floor(p.xyz * 255.0 + 0.5);
#if JD_PACK_HIGHP
    return (b.x + (b.y + b.z / 255.0) / 255.0) / 255.0;
#else
    return (b.x + b.y / 255.0) / 255.0;
#endif
}

// A packed depth's first two bytes as high byte + low byte / 255:
// dot(texel.xy, jd_bytes). Without jd_unpack's exact recovery of the bytes,
// where a texture unit's error of 1e-5 is nothing beside what reads it (a
// shadow test's bias, a blur, fp16) and the recovery costs instruction
// words (light.glsl, jd_lit_fraction).
const vec2 jd_bytes = vec2(1.0, 1.0 / 255.0);

// The same from the whole texel, the two bytes weighed by w (jd_bytes, or
// those times a scale). Where depth is packed in two bytes the third
// channel holds 0, and three channels by one dot product are one of lima's
// instruction words where two took a multiply and an add (the third weight
// is any but a constant 0, which the compiler would drop). With the
// three-byte packing (VideoCore IV, Adreno 3xx, Vivante, where two lanes
// were the shorter) the first two bytes, as above.
float jd_depth_by(vec4 texel, vec2 w)
{
#if JD_PACK_HIGHP
    return dot(texel.xy, w);
#else
    return dot(texel.xyz, vec3(w, w.y));
#endif
}
float jd_depth(vec4 texel)
{
    return jd_depth_by(texel, jd_bytes);
}

// Signed values in [-1,1], for the SH reduction. highp: the 3-byte packing of
// s/2 + 0.5. mediump: an offset of 0.5 would spend fp16's 11 bits on the
// offset, so the positive and negative parts get two bytes each and small
// values keep their relative precision.
vec4 jd_pack_signed(float s)
{
#if JD_PACK_HIGHP
    return jd_pack(s * 0.5 + 0.5);
#else
    // Both magnitudes at once in whole-vector operations (lanes: positive
    // part's two bytes, negative part's two): a vec4 assembled from two
    // halves made lima keep extra registers live. Multiplying by exact 0s
    // and 1s selects each lane's value without rounding.
    vec4 a = clamp(s * vec4(1.0, 1.0, -1.0, -1.0), 0.0, 1.0) * 255.0;
    vec4 b = floor(a);
    const vec4 low = vec4(0.0, 1.0, 0.0, 1.0);
    return b / 255.0 * (1.0 - low) + (a - b) * low;
#endif
}

float jd_unpack_signed(vec4 p)
{
#if JD_PACK_HIGHP
    return jd_unpack(p) * 2.0 - 1.0;
#else
    vec4 b = floor(p * 255.0 + 0.5);
    return (b.x / 255.0 + b.y / 65025.0) - (b.z / 255.0 + b.w / 65025.0);
#endif
}

// The luma the pass after the frame tests its edges by (antialias.frag), of
// display-encoded colours; shade.frag writes it to the frame's alpha where
// that pass reads it there (JD_LUMA_ALPHA), pass_screen.c the clear's.
#define JD_LUMA vec3(0.299, 0.587, 0.114)
