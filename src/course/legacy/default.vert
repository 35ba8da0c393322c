// shaderlab legacy: the built-in demo pair (GLSL 1.10). Per-pixel Blinn-Phong with GL's own
// light 0 and front material; run your own with `legacy VERT FRAG`.
varying vec3 N;
varying vec3 P;

void main()
{
    P = vec3(gl_ModelViewMatrix * gl_Vertex);
    N = normalize(gl_NormalMatrix * gl_Normal);
    gl_Position = ftransform();
}
