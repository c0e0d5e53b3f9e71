#version 100
// Light-space depth, linear (orthographic light), normalised to the object.
attribute vec3 a_position;
uniform mat4 u_light_mvp;
varying float v_depth;
void main()
{
    gl_Position = u_light_mvp * vec4(a_position, 1.0);
    v_depth = gl_Position.z * 0.5 + 0.5;
}
