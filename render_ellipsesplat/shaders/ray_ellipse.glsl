// Equation (1) of the paper, [E F v] (x, y, -t)^T = -p, solved with the dual basis of (E, F)
// in the splat plane that splat.vert.glsl prepared: t from the plane, then x and y.
// Needs viewing_ray.glsl before it.
flat in vec3 splatCenter;
flat in vec3 planeNormal;
flat in vec3 dualMajor; // dot(q, dualMajor) = x for q = x E + y F
flat in vec3 dualMinor; // dot(q, dualMinor) = y
flat in vec3 shadingNormal;
flat in vec4 splatColor;
flat in float depthOffset;

bool intersectSplat(out vec3 hit, out vec3 direction, out float radiusSquared)
{
    vec3 origin;
    viewingRay(origin, direction);
    float along = dot(planeNormal, direction);
    if (along == 0.0)
        return false;
    hit = origin + direction * (dot(planeNormal, splatCenter - origin) / along);
    vec3 inPlane = hit - splatCenter;
    float x = dot(inPlane, dualMajor);
    float y = dot(inPlane, dualMinor);
    radiusSquared = x * x + y * y;
    return radiusSquared <= 1.0;
}
