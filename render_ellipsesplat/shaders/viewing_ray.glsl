// The eye-space viewing ray through this fragment (works for perspective and orthographic
// projections), and the window depth of an eye-space point. Fragment stages only.
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
