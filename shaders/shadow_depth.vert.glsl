// Shadow pass: one layer of a light's shadow-map array, depth only.
layout(location = 0) in vec3 inPosition;

uniform mat4 uLightFromLocal;  // object -> light view (m)
uniform mat4 uClipFromLight;

out vec3 vLsPosition;

void main() {
    vec4 ls = uLightFromLocal * vec4(inPosition, 1.0);
    vLsPosition = ls.xyz;
    gl_Position = uClipFromLight * ls;
}
