#version 100
varying float v_depth;
varying float v_irr;
void main()
{
    // Depth in the colour channels (two or three bytes, jd_pack), the
    // irradiance in alpha, which the packing leaves free.
    gl_FragColor = vec4(jd_pack(v_depth).rgb, v_irr);
}
