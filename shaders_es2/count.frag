#version 100
// One count per fragment, added (blending ONE, ONE) into an RGBA8 target:
// 1/255 becomes one step of red.
void main()
{
    gl_FragColor = vec4(1.0 / 255.0, 0.0, 0.0, 0.0);
}
