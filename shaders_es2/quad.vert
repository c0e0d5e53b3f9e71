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
void main()
{
    v_uv = (a_corner * 0.5 + 0.5) * u_uv_scale;
#ifdef JD_DIAGONALS
    v_diag0 = v_uv.xyxy + vec4(-1.0, -1.0, 1.0, -1.0) * u_texel.xyxy;
    v_diag1 = v_uv.xyxy + vec4(-1.0, 1.0, 1.0, 1.0) * u_texel.xyxy;
#endif
    gl_Position = vec4(a_corner, 0.0, 1.0);
}
