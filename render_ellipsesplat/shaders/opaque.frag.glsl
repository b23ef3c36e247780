#version 330
// One-pass mode: the nearest splat wins, lit with its own normal.
#include "viewing_ray.glsl"
#include "ray_ellipse.glsl"
#include "lighting.glsl"

out vec4 fragColor;

void main()
{
    vec3 hit, direction;
    float radiusSquared, depth;
    if (!intersectSplat(hit, direction, radiusSquared) || !windowDepth(hit, depth))
        discard;
    gl_FragDepth = depth;
    fragColor = vec4(shade(splatColor.rgb, shadingNormal, -normalize(direction)), 1.0);
}
