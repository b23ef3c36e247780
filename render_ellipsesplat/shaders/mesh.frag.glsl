#version 330
// Reference meshes: flat (per-face normal from screen derivatives) or Phong shading.
#include "lighting.glsl"

uniform mat4 projection;
uniform bool flatShading;

in vec3 eyePosition;
in vec3 eyeNormal;
in vec4 vertexColor;
out vec4 fragColor;

void main()
{
    vec3 n = flatShading ? cross(dFdx(eyePosition), dFdy(eyePosition)) : eyeNormal;
    vec3 towardsEye = projection[3][3] == 0.0 ? -normalize(eyePosition) : vec3(0.0, 0.0, 1.0);
    fragColor = vec4(shade(vertexColor.rgb, n, towardsEye), 1.0);
}
