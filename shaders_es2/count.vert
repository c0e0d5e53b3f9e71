#version 100
// The frame-cost count (jd_renderer_count): a mesh pass's positions under
// its own transform, exactly as mesh.vert, depth.vert and capture.vert
// compute them, so the same fragments pass the depth test.
attribute vec3 a_position;
uniform mat4 u_mvp;

void main()
{
    gl_Position = u_mvp * vec4(a_position, 1.0);
}
