#version 100
// full's levels' sum (shade.frag, JD_WIDE_ONLY) with its outline filled: a
// texel the light map's proxy did not cover takes the mean of the covered
// ones among its eight neighbours, so that the shading's one bilinear read
// needs no division by coverage (lima 26 -> 23 words a fragment there, at
// the picture's count of fragments, where this runs at the layer's: an
// eighth to a half of its resolution). The four reads half a texel off on
// the diagonals each average a 2 x 2 block: the neighbours weighed 1, 2, 1
// across and down. A texel with no covered neighbour stays 0 (no light),
// as the division's guard had it.
precision mediump float;
uniform sampler2D u_src;    // sqrt(wide / 2), alpha = covered (1) or not (0); bilinear
varying vec2 v_uv;
varying vec4 v_diag0;       // half a texel off: (-1, -1) and (1, -1) (quad.vert, JD_DIAGONALS)
varying vec4 v_diag1;       // (-1, 1) and (1, 1)

void main()
{
    vec4 c = texture2D(u_src, v_uv);
    vec4 s = texture2D(u_src, v_diag0.xy) + texture2D(u_src, v_diag0.zw) + texture2D(u_src, v_diag1.xy) +
             texture2D(u_src, v_diag1.zw);
    gl_FragColor = c.a > 0.5 ? c : vec4(s.rgb / max(s.a, 0.01), 0.0);
}
