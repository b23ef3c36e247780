#version 330
// Pass 1 of three: the depth of the visible surface, every splat pushed back by its epsilon
// along the viewing ray.
#include "viewing_ray.glsl"
#include "ray_ellipse.glsl"

void main()
{
    vec3 hit, direction;
    float radiusSquared, depth;
    if (!intersectSplat(hit, direction, radiusSquared) ||
        !windowDepth(hit + normalize(direction) * depthOffset, depth))
        discard;
    gl_FragDepth = depth;
}
