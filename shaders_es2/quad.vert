#version 100
attribute vec2 a_corner;
uniform vec2 u_uv_scale;    // used part of a power-of-two source texture
varying vec2 v_uv;
#ifdef JD_DIAGONALS
// The four diagonal neighbours' coordinates, for a program that reads them
// (antialias.frag): interpolated, they cost the fragment stage no
// instruction, and the reads need not wait for one.
uniform mediump vec2 u_texel; // 1 / the source texture's size; mediump as the fragment stage declares it
varying vec4 v_diag0;       // (-1, -1) and (1, -1) texels from v_uv
varying vec4 v_diag1;       // (-1, 1) and (1, 1)
#endif
#ifdef JD_BOX_COORDS
// The first diffusion step's squares unrolled (diffuse_blur.frag): each
// light-map texel's coordinates, the square's origin, across, up and both,
// as that program's loop placed them (its trips, JD_BOX_SIDE a side).
uniform mediump vec2 u_step; // a light-map texel; mediump as the fragment stage declares it
varying vec4 v_sq[2 * JD_TRIPS];
#endif
void main()
{
    v_uv = (a_corner * 0.5 + 0.5) * u_uv_scale;
#ifdef JD_DIAGONALS
    v_diag0 = v_uv.xyxy + vec4(-1.0, -1.0, 1.0, -1.0) * u_texel.xyxy;
    v_diag1 = v_uv.xyxy + vec4(-1.0, 1.0, 1.0, 1.0) * u_texel.xyxy;
#endif
#ifdef JD_BOX_COORDS
    const float hb = 0.5 * float(JD_BOX_SIDE);
    for (int i = 0; i < JD_TRIPS; i++) {
        float fi = float(i), row = floor(fi * (1.0 / hb));
        vec2 o = v_uv + (2.0 * vec2(fi - hb * row, row) - 0.5 * (float(JD_BOX_SIDE) - 1.0)) * u_step;
        v_sq[2 * i] = vec4(o, o + vec2(u_step.x, 0.0));
        v_sq[2 * i + 1] = vec4(o + vec2(0.0, u_step.y), o + u_step);
    }
#endif
    gl_Position = vec4(a_corner, 0.0, 1.0);
}
