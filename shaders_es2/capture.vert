#version 100
// One face of the bounding-cube capture: the object under direct light only.
attribute vec3 a_position;
attribute vec3 a_normal;
uniform mat4 u_mvp;
uniform mat4 u_light_tex;   // to light-map coordinates (mesh.vert)
uniform vec3 u_light_dir;
uniform float u_bias;
varying float v_ndl;
varying vec3 v_light;
void main()
{
    gl_Position = u_mvp * vec4(a_position, 1.0);
    v_ndl = max(dot(a_normal, u_light_dir), 0.0);
    v_light = (u_light_tex * vec4(a_position, 1.0)).xyz;
    v_light.z -= u_bias;
}
