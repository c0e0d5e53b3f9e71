#version 100
// The six taps of soft_shadow.frag, where the vertices compute them: a
// fragment program that reads its textures at varyings as they come spends
// no instruction on their coordinates.
attribute vec2 a_corner;
uniform vec2 u_uv_scale;    // used part of the power-of-two source texture
uniform vec2 u_step;        // one light-map texel along the pass's direction
varying vec4 v_a, v_b, v_c; // taps -2.5, -1.5 | -0.5, 0.5 | 1.5, 2.5 texels away
void main()
{
    vec2 uv = (a_corner * 0.5 + 0.5) * u_uv_scale;
    v_a = vec4(uv - 2.5 * u_step, uv - 1.5 * u_step);
    v_b = vec4(uv - 0.5 * u_step, uv + 0.5 * u_step);
    v_c = vec4(uv + 1.5 * u_step, uv + 2.5 * u_step);
    gl_Position = vec4(a_corner, 0.0, 1.0);
}
