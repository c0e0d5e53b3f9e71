#version 100
// The frame drawn at a lower resolution (jd_renderer_desc.render_scale),
// enlarged to the target's: one bilinear read per pixel, the cheapest pass
// a GPU can run at full resolution (where the display engine cannot scale
// the picture itself).
uniform sampler2D u_src;    // the frame, display-encoded, bilinear
varying vec2 v_uv;

void main()
{
    gl_FragColor = texture2D(u_src, v_uv); // its alpha is 1: the frame is opaque
}
