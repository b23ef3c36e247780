#include "splat_shaders.h"

namespace splat {
namespace shaders {
namespace {

const char *const kVersion = "#version 330\n";

// Blinn-Phong with one directional light, two-sided: the same in every mode so that splats,
// points and reference meshes are comparable pixel for pixel.
const char *const kLighting = R"(
uniform vec3 towardsLight;
uniform vec3 lightAmbient;
uniform vec3 lightDiffuse;
uniform vec3 lightSpecular;
uniform float shininess;

vec3 shade(vec3 albedo, vec3 normal, vec3 towardsEye)
{
    vec3 n = dot(normal, normal) > 0.0 ? normalize(normal) : towardsEye;
    if (dot(n, towardsEye) < 0.0)
        n = -n;
    vec3 l = normalize(towardsLight);
    float diffuse = max(dot(n, l), 0.0);
    float specular = diffuse > 0.0 ? pow(max(dot(n, normalize(l + towardsEye)), 0.0), shininess) : 0.0;
    return albedo * (lightAmbient + lightDiffuse * diffuse) + lightSpecular * specular;
}
)";

// The eye-space viewing ray through this fragment (works for perspective and orthographic
// projections), and the window depth of an eye-space point.
const char *const kViewingRay = R"(
uniform mat4 projection;
uniform mat4 inverseProjection;
uniform vec4 viewport; // x, y, width, height of the framebuffer area being drawn

void viewingRay(out vec3 origin, out vec3 direction)
{
    vec2 ndc = (gl_FragCoord.xy - viewport.xy) / viewport.zw * 2.0 - 1.0;
    vec4 nearPoint = inverseProjection * vec4(ndc, -1.0, 1.0);
    vec4 farPoint = inverseProjection * vec4(ndc, 1.0, 1.0);
    origin = nearPoint.xyz / nearPoint.w;
    direction = farPoint.xyz / farPoint.w - origin;
}

// False when the point lies outside the near/far range (it would be clipped).
bool windowDepth(vec3 eyePoint, out float depth)
{
    vec4 clip = projection * vec4(eyePoint, 1.0);
    float ndcZ = clip.z / clip.w;
    depth = 0.5 * (gl_DepthRange.diff * ndcZ + gl_DepthRange.near + gl_DepthRange.far);
    return clip.w > 0.0 && abs(ndcZ) <= 1.0;
}
)";

// Equation (1) of the paper, [E F v]·(x, y, −t)ᵀ = −p, solved with the dual basis of (E, F)
// in the splat plane that the vertex shader prepared: t from the plane, then x and y.
const char *const kRayEllipse = R"(
flat in vec3 splatCenter;
flat in vec3 planeNormal;
flat in vec3 dualMajor; // dot(q, dualMajor) = x for q = x·E + y·F
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
)";

} // namespace

std::string splatVertex()
{
    return std::string(kVersion) + R"(
layout(location = 0) in vec3 center;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 majorAxis;
layout(location = 3) in vec3 minorAxis;
layout(location = 4) in vec4 color;

uniform mat4 modelView;
uniform mat3 normalMatrix;
uniform mat4 projection;
uniform vec4 viewport;
uniform float splatScale;
uniform float depthOffsetFactor;
uniform bool cullBackFaces;

flat out vec3 splatCenter;
flat out vec3 planeNormal;
flat out vec3 dualMajor;
flat out vec3 dualMinor;
flat out vec3 shadingNormal;
flat out vec4 splatColor;
flat out float depthOffset;

const vec2 corners[4] = vec2[4](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0), vec2(1.0, 1.0));

void skipSplat()
{
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // all four corners outside the clip volume
}

void main()
{
    vec3 p = (modelView * vec4(center, 1.0)).xyz;
    vec3 e = mat3(modelView) * majorAxis * splatScale;
    vec3 f = mat3(modelView) * minorAxis * splatScale;
    vec3 n = normalMatrix * normal;
    vec3 ef = cross(e, f);
    float lengthSquaredE = dot(e, e);
    if (dot(n, n) == 0.0 || dot(ef, ef) <= 1e-12 * lengthSquaredE * lengthSquaredE) {
        skipSplat(); // no orientation or no area
        return;
    }
    vec3 m = dot(ef, n) < 0.0 ? -ef : ef; // plane normal, on the side of the surfel normal
    vec3 rayAtCenter = projection[3][3] == 0.0 ? p : vec3(0.0, 0.0, -1.0);
    bool backFacing = dot(m, rayAtCenter) > 0.0;
    if (backFacing && cullBackFaces) {
        skipSplat();
        return;
    }

    // The ellipse lies inside the parallelogram p ± E ± F; perspective keeps it inside the
    // projected parallelogram, so the screen box of the four projected corners is safe.
    vec2 lo = vec2(1e30);
    vec2 hi = vec2(-1e30);
    int cornersBehindEye = 0;
    for (int i = 0; i < 4; ++i) {
        vec4 clip = projection * vec4(p + corners[i].x * e + corners[i].y * f, 1.0);
        if (clip.w <= 0.0) {
            ++cornersBehindEye;
        } else {
            lo = min(lo, clip.xy / clip.w);
            hi = max(hi, clip.xy / clip.w);
        }
    }
    if (cornersBehindEye == 4) {
        skipSplat();
        return;
    }
    if (cornersBehindEye > 0) { // the projection wraps through infinity: take the whole screen
        lo = vec2(-1.0);
        hi = vec2(1.0);
    }
    vec2 halfPixel = 1.0 / viewport.zw;
    lo = max(lo - halfPixel, vec2(-1.0));
    hi = min(hi + halfPixel, vec2(1.0));
    if (any(greaterThan(lo, hi))) {
        skipSplat(); // off screen
        return;
    }
    gl_Position = vec4(mix(lo, hi, corners[gl_VertexID] * 0.5 + 0.5), 0.0, 1.0);

    splatCenter = p;
    planeNormal = m;
    vec3 fm = cross(f, m);
    vec3 me = cross(m, e);
    dualMajor = fm / dot(e, fm);
    dualMinor = me / dot(f, me);
    shadingNormal = normalize(backFacing ? -n : n);
    splatColor = color;
    depthOffset = depthOffsetFactor * sqrt(lengthSquaredE);
}
)";
}

std::string visibilityFragment()
{
    return std::string(kVersion) + kViewingRay + kRayEllipse + R"(
void main()
{
    vec3 hit, direction;
    float radiusSquared, depth;
    if (!intersectSplat(hit, direction, radiusSquared) ||
        !windowDepth(hit + normalize(direction) * depthOffset, depth))
        discard;
    gl_FragDepth = depth;
}
)";
}

std::string accumulationFragment()
{
    return std::string(kVersion) + kViewingRay + kRayEllipse + R"(
layout(location = 0) out vec4 colorSum;       // (w·rgb, w)
layout(location = 1) out vec4 normalDepthSum; // (w·normal, w·depth)

// Gaussian weight over the ellipse, exp(-2) ≈ 0.14 on its border.
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
)";
}

std::string normalizationVertex()
{
    return std::string(kVersion) + R"(
layout(location = 0) in vec2 corner;
void main()
{
    gl_Position = vec4(corner, 0.0, 1.0);
}
)";
}

std::string normalizationFragment()
{
    return std::string(kVersion) + kViewingRay + kLighting + R"(
uniform sampler2D colorSums;
uniform sampler2D normalDepthSums;
out vec4 fragColor;

void main()
{
    ivec2 texel = ivec2(gl_FragCoord.xy - viewport.xy);
    vec4 colorSum = texelFetch(colorSums, texel, 0);
    if (colorSum.a <= 0.0)
        discard; // no splat here: keep what the framebuffer holds
    vec4 normalDepthSum = texelFetch(normalDepthSums, texel, 0);
    vec3 origin, direction;
    viewingRay(origin, direction);
    fragColor = vec4(shade(colorSum.rgb / colorSum.a, normalDepthSum.xyz, -normalize(direction)), 1.0);
    gl_FragDepth = normalDepthSum.w / colorSum.a;
}
)";
}

std::string opaqueFragment()
{
    return std::string(kVersion) + kViewingRay + kRayEllipse + kLighting + R"(
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
)";
}

std::string pointVertex()
{
    return std::string(kVersion) + kLighting + R"(
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
)";
}

std::string pointFragment()
{
    return std::string(kVersion) + R"(
in vec4 litColor;
out vec4 fragColor;
void main()
{
    fragColor = litColor;
}
)";
}

std::string meshVertex()
{
    return std::string(kVersion) + R"(
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
)";
}

std::string meshFragment()
{
    return std::string(kVersion) + kLighting + R"(
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
)";
}

} // namespace shaders
} // namespace splat
