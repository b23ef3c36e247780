#pragma once
// GLSL sources of the splat renderer (GLSL 3.30, runs in core and compatibility contexts).

#include <string>

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

std::string splatVertex();        // bounding quad of each projected ellipse
std::string visibilityFragment(); // pass 1: ε-offset depth
std::string accumulationFragment(); // pass 2: weighted sums into float targets
std::string normalizationVertex();  // pass 3: full-screen triangle
std::string normalizationFragment();
std::string opaqueFragment();       // one-pass: nearest splat, lit on its own
std::string pointVertex();
std::string pointFragment();
std::string meshVertex();
std::string meshFragment();

} // namespace shaders
} // namespace splat
