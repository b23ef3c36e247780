#version 330
// Pass 2 of three: Gaussian-weighted sums of colour, normal and depth of every splat within
// epsilon of the visible surface, added into float render targets.
#include "viewing_ray.glsl"
#include "ray_ellipse.glsl"

layout(location = 0) out vec4 colorSum;       // (w rgb, w)
layout(location = 1) out vec4 normalDepthSum; // (w normal, w depth)

// Gaussian weight over the ellipse, exp(-2) = 0.14 on its border.
const float gaussianFalloff = 2.0;

void main()
{
    vec3 hit, direction;
    float radiusSquared, depth;
    if (!intersectSplat(hit, direction, radiusSquared) || !windowDepth(hit, depth))
        discard;
    gl_FragDepth = depth;
    float weight = exp(-gaussianFalloff * radiusSquared);
    colorSum = vec4(splatColor.rgb * weight, weight);
    normalDepthSum = vec4(shadingNormal * weight, depth * weight);
}
