#version 330
// Pass 3 of three: the sums of pass 2 divided by their weight, lit, with their depth.
#include "viewing_ray.glsl"
#include "lighting.glsl"

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
