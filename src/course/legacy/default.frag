// shaderlab legacy: the built-in demo pair (GLSL 1.10).
varying vec3 N;
varying vec3 P;

void main()
{
    vec3 n = normalize(N);
    vec3 l = normalize(gl_LightSource[0].position.xyz - P * gl_LightSource[0].position.w);
    vec3 h = normalize(l + normalize(-P));
    float diffuse = max(dot(n, l), 0.0);
    float specular = diffuse > 0.0 ? pow(max(dot(n, h), 0.0), gl_FrontMaterial.shininess) : 0.0;
    gl_FragColor = gl_FrontLightModelProduct.sceneColor
        + gl_FrontLightProduct[0].ambient
        + diffuse * gl_FrontLightProduct[0].diffuse
        + specular * gl_FrontLightProduct[0].specular;
}
