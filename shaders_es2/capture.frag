#version 100
uniform sampler2D u_depth;
uniform vec3 u_light_color;
varying float v_ndl;
varying vec3 v_light;
void main()
{
    // Surfaces behind other parts of the object, as seen from the light, are
    // in shadow: without this a concave shape would glow from inside.
    float lit = v_light.z <= jd_unpack(texture2D(u_depth, v_light.xy)) ? 1.0 : 0.0;
    gl_FragColor = vec4(lit * v_ndl * u_light_color, 1.0);
}
