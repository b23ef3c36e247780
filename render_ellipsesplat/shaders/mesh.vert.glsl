#version 330
// Reference meshes (ShadedMeshRenderer), lit exactly like the splats.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec4 color;

uniform mat4 modelView;
uniform mat3 normalMatrix;
uniform mat4 projection;

out vec3 eyePosition;
out vec3 eyeNormal;
out vec4 vertexColor;

void main()
{
    vec4 p = modelView * vec4(position, 1.0);
    gl_Position = projection * p;
    eyePosition = p.xyz;
    eyeNormal = normalMatrix * normal;
    vertexColor = color;
}
