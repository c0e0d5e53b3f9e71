#version 100
// Light-space depth, linear (orthographic light), normalised to the object;
// and the irradiance the lit surface takes in, for the full mode's diffusion.
attribute vec3 a_position;
attribute vec3 a_normal;
uniform mat4 u_light_mvp;
uniform vec3 u_light_dir;
uniform vec2 u_fresnel;      // jd_fresnel_tc's fit at the scene's eta
varying float v_depth;
varying float v_irr;
void main()
{
    gl_Position = u_light_mvp * vec4(a_position, 1.0);
    v_depth = gl_Position.z * 0.5 + 0.5;
    // N.L Ft(N.L) / c, c the mean of Ft under diffuse light: the reference's
    // irradiance per unit area of surface. At most 21/20 (the fit's
    // u_fresnel.x is at most 1.049 over eta 1..3): stored
    // over that, as a square root, so dim light keeps its precision in 8 bits.
    float ndl = max(dot(a_normal, u_light_dir), 0.0);
    v_irr = sqrt(clamp(ndl * jd_fresnel_tc(ndl, u_fresnel) * (20.0 / 21.0), 0.0, 1.0));
}
