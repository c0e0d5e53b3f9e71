#version 100
attribute vec2 a_corner;
uniform vec2 u_uv_scale;    // used part of a power-of-two source texture
varying vec2 v_uv;
void main()
{
    v_uv = (a_corner * 0.5 + 0.5) * u_uv_scale;
    gl_Position = vec4(a_corner, 0.0, 1.0);
}
