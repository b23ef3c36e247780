#pragma once
// GLSL sources of the splat renderer (GLSL 3.30, runs in core and compatibility contexts).
// Each stage is the file shaders/<name>.vert.glsl or shaders/<name>.frag.glsl, embedded at
// build time by embed_shaders.cmake with its #include lines expanded.

namespace splat {
namespace shaders {

// Per-instance splat attributes, bound by SplatCloud at these locations.
enum AttributeLocation
{
    kCenter = 0,
    kNormal = 1,
    kMajorAxis = 2,
    kMinorAxis = 3,
    kColor = 4,
};

struct ShaderSource
{
    const char *text;
    // What the source string numbers of the text's #line directives (the S of a compiler's
    // "S:line" message) stand for, e.g. "0: opaque.frag.glsl, 1: viewing_ray.glsl".
    const char *sourceStrings;
};

ShaderSource splatVertex();          // splat.vert.glsl: bounding quad of each projected ellipse
ShaderSource visibilityFragment();   // pass 1: epsilon-offset depth
ShaderSource accumulationFragment(); // pass 2: weighted sums into float targets
ShaderSource normalizationVertex();  // pass 3: full-screen triangle
ShaderSource normalizationFragment();
ShaderSource opaqueFragment();       // one-pass: nearest splat, lit on its own
ShaderSource pointVertex();
ShaderSource pointFragment();
ShaderSource meshVertex();
ShaderSource meshFragment();

} // namespace shaders
} // namespace splat
