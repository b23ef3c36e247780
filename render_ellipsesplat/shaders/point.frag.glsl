#version 330
// Points mode: the colour lit in the vertex stage.
in vec4 litColor;
out vec4 fragColor;

void main()
{
    fragColor = litColor;
}
