#version 330
// Pass 3 of three: a full-screen triangle.
layout(location = 0) in vec2 corner;

void main()
{
    gl_Position = vec4(corner, 0.0, 1.0);
}
