#version 330
// The bounding quad of each projected ellipse (one instance per splat, four vertices), and
// what the fragment stages need to intersect a pixel's viewing ray with the ellipse.

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

    // The ellipse lies inside the parallelogram p +- E +- F; perspective keeps it inside the
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
