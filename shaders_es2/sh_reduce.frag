#version 100
// Later SH reduction steps: each output pixel is the mean of an RX x RY block
// of packed values (defines JD_RX, JD_RY).
uniform sampler2D u_src;
uniform vec2 u_src_texel;  // 1 / source size
void main()
{
    vec2 base = floor(gl_FragCoord.xy) * vec2(float(JD_RX), float(JD_RY));
    float sum = 0.0;
    for (int j = 0; j < JD_RY; j++)
        for (int i = 0; i < JD_RX; i++)
            sum += jd_unpack_signed(texture2D(u_src, (base + vec2(float(i), float(j)) + 0.5) * u_src_texel))
                   / float(JD_RX * JD_RY);
    gl_FragColor = jd_pack_signed(sum);
}
