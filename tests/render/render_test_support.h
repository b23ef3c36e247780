#pragma once
// Scenes with known answers for the splat renderer tests: analytic spheres sampled into
// surfels, a CPU ray caster for single ellipses, and image measurements.

#include "ellipse_splat_renderer.h"
#include "offscreen_gl.h"
#include "orbit_camera.h"

#include <Eigen/Dense>
#include <QImage>

#include <vector>

namespace splat {
namespace test {

struct Sphere
{
    Eigen::Vector3f center;
    float radius;
};

// n surfels on a Fibonacci spiral over the sphere (near-uniform spacing), outward normals,
// circular splats sized by nearestNeighbourRadii.
SurfelArrays sampleSphere(const Sphere &sphere, int n, const std::uint8_t rgba[4]);

// One rendered frame: colour (top row first) and window depth (bottom row first, as GL).
struct Frame
{
    QImage color;
    std::vector<float> depth;
    int width, height;
    bool covered(int x, int y) const { return depthAt(x, y) < 1.0f; } // x, y: image coordinates, top row 0
    float depthAt(int x, int y) const { return depth[std::size_t(height - 1 - y) * width + x]; }
    float luminance(int x, int y) const;
};

Frame renderSplats(EllipseSplatRenderer &renderer, const std::vector<const SplatCloud *> &clouds, const Camera &camera,
                   int width, int height, const SplatSettings &settings);

// The eye-space ray through the centre of image pixel (x, y), top row 0.
void pixelRay(const Camera &camera, int width, int height, int x, int y, Eigen::Vector3f &origin,
              Eigen::Vector3f &direction);

// Per pixel: does the ray hit the sphere, and at what eye distance (-z)?
struct AnalyticImage
{
    std::vector<bool> inside; // top row first
    std::vector<float> distance;
};
AnalyticImage castSphere(const Sphere &sphere, const Camera &camera, int width, int height);

// The mask shrunk by `pixels` (a pixel stays only if all pixels within that Chebyshev distance are set).
std::vector<bool> erode(const std::vector<bool> &mask, int width, int height, int pixels);

// Per-pixel visibility of one ellipse cast on the CPU exactly as equation (1) says.
std::vector<bool> castEllipse(const Eigen::Vector3f &center, const Eigen::Vector3f &major,
                              const Eigen::Vector3f &minor, const Camera &camera, int width, int height);

// Largest luminance step between 4-neighbours with both pixels inside `mask`: the seams
// between splats show up as steps, smooth shading has only small ones.
struct Steps
{
    float largest;
    float percentile99;
};
Steps luminanceSteps(const Frame &frame, const std::vector<bool> &mask);

} // namespace test
} // namespace splat
