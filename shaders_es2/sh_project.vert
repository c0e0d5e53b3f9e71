#version 100
// First SH reduction step, drawn as one rectangle per (cube face, coefficient
// row): everything that is constant over a rectangle (the coefficient's
// polynomial on that face, the colour channel, where the face lies in the
// atlas) comes as attributes, so the fragment shader keeps few values live
// (Mali-400 and VideoCore IV have small register files).
attribute vec2 a_corner;   // clip space
attribute vec4 a_poly0;    // Y_k on this face as c0 + c1 fx + c2 fy + c3 fx^2 ...
attribute vec4 a_poly1;    // ... + c4 fy^2 + c5 fx fy, then the power of q (see the .frag)
attribute vec3 a_channel;  // which of r, g, b this row projects
attribute vec4 a_texel;    // xy: atlas texel of the block's first sample (+ 0.5 at pixel centres); zw: the face's corner
varying vec4 v_poly0;
varying vec4 v_poly1;
varying vec3 v_channel;
varying vec4 v_texel;
void main()
{
    v_poly0 = a_poly0;
    v_poly1 = a_poly1;
    v_channel = a_channel;
    v_texel = a_texel;
    gl_Position = vec4(a_corner, 0.0, 1.0);
}
