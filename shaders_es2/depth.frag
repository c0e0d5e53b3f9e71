#version 100
varying float v_depth;
void main()
{
    gl_FragColor = jd_pack(v_depth);
}
