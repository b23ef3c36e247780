#version 330
// Points mode: fixed-size GL points, lit per point.
#include "lighting.glsl"

layout(location = 0) in vec3 center;
layout(location = 1) in vec3 normal;
layout(location = 4) in vec4 color;

uniform mat4 modelView;
uniform mat3 normalMatrix;
uniform mat4 projection;
uniform float pointSize;

out vec4 litColor;

void main()
{
    vec4 p = modelView * vec4(center, 1.0);
    gl_Position = projection * p;
    gl_PointSize = pointSize;
    vec3 towardsEye = projection[3][3] == 0.0 ? -normalize(p.xyz) : vec3(0.0, 0.0, 1.0);
    litColor = vec4(shade(color.rgb, normalMatrix * normal, towardsEye), 1.0);
}
