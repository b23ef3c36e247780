#include "render_test_support.h"

#include <algorithm>
#include <cmath>

namespace splat {
namespace test {

SurfelArrays sampleSphere(const Sphere &sphere, int n, const std::uint8_t rgba[4])
{
    SurfelArrays s;
    const float goldenAngle = 3.14159265f * (3.0f - std::sqrt(5.0f));
    for (int i = 0; i < n; ++i) {
        const float y = 1.0f - 2.0f * (i + 0.5f) / n;
        const float r = std::sqrt(1.0f - y * y);
        const Eigen::Vector3f normal(r * std::cos(goldenAngle * i), y, r * std::sin(goldenAngle * i));
        const Eigen::Vector3f p = sphere.center + sphere.radius * normal;
        s.positions.insert(s.positions.end(), p.data(), p.data() + 3);
        s.normals.insert(s.normals.end(), normal.data(), normal.data() + 3);
        s.colors.insert(s.colors.end(), rgba, rgba + 4);
    }
    assignCircularFrames(s, nearestNeighbourRadii(s.positions, kDefaultSplatNeighbours));
    return s;
}

float Frame::luminance(int x, int y) const
{
    const QRgb c = color.pixel(x, y);
    return 0.299f * qRed(c) + 0.587f * qGreen(c) + 0.114f * qBlue(c);
}

Frame renderSplats(EllipseSplatRenderer &renderer, const std::vector<const SplatCloud *> &clouds, const Camera &camera,
                   int width, int height, const SplatSettings &settings)
{
    RenderTarget target(width, height);
    const float black[4] = {0, 0, 0, 1};
    target.clear(black);
    std::vector<SplatDrawItem> items;
    for (const SplatCloud *cloud : clouds) {
        SplatDrawItem item{cloud, {}};
        std::copy(camera.modelView, camera.modelView + 16, item.modelView);
        items.push_back(item);
    }
    renderer.render(items, camera.projection, {0, 0, width, height}, Lighting(), settings);
    return Frame{target.readColor(), target.readDepth(), width, height};
}

void pixelRay(const Camera &camera, int width, int height, int x, int y, Eigen::Vector3f &origin,
              Eigen::Vector3f &direction)
{
    const Eigen::Matrix4f inverse = Eigen::Map<const Eigen::Matrix4f>(camera.projection).inverse();
    const float ndcX = (x + 0.5f) / width * 2.0f - 1.0f;
    const float ndcY = (height - 1 - y + 0.5f) / height * 2.0f - 1.0f;
    const Eigen::Vector4f nearPoint = inverse * Eigen::Vector4f(ndcX, ndcY, -1, 1);
    const Eigen::Vector4f farPoint = inverse * Eigen::Vector4f(ndcX, ndcY, 1, 1);
    origin = nearPoint.head<3>() / nearPoint.w();
    direction = farPoint.head<3>() / farPoint.w() - origin;
}

AnalyticImage castSphere(const Sphere &sphere, const Camera &camera, int width, int height)
{
    const Eigen::Matrix4f view = Eigen::Map<const Eigen::Matrix4f>(camera.modelView);
    const Eigen::Vector3f c = (view * sphere.center.homogeneous()).head<3>(); // rigid view: radius unchanged
    AnalyticImage image{std::vector<bool>(std::size_t(width) * height, false),
                        std::vector<float>(std::size_t(width) * height, 0.0f)};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            Eigen::Vector3f o, d;
            pixelRay(camera, width, height, x, y, o, d);
            d.normalize();
            const float along = (c - o).dot(d);
            const float missSquared = (c - o).squaredNorm() - along * along;
            const float r2 = sphere.radius * sphere.radius;
            if (missSquared >= r2)
                continue;
            const Eigen::Vector3f hit = o + d * (along - std::sqrt(r2 - missSquared));
            image.inside[std::size_t(y) * width + x] = true;
            image.distance[std::size_t(y) * width + x] = -hit.z();
        }
    return image;
}

std::vector<bool> erode(const std::vector<bool> &mask, int width, int height, int pixels)
{
    std::vector<bool> result(mask.size(), false);
    for (int y = pixels; y < height - pixels; ++y)
        for (int x = pixels; x < width - pixels; ++x) {
            bool all = true;
            for (int dy = -pixels; dy <= pixels && all; ++dy)
                for (int dx = -pixels; dx <= pixels && all; ++dx)
                    all = mask[std::size_t(y + dy) * width + x + dx];
            result[std::size_t(y) * width + x] = all;
        }
    return result;
}

std::vector<bool> castEllipse(const Eigen::Vector3f &center, const Eigen::Vector3f &major,
                              const Eigen::Vector3f &minor, const Camera &camera, int width, int height)
{
    const Eigen::Matrix4f view = Eigen::Map<const Eigen::Matrix4f>(camera.modelView);
    const Eigen::Matrix4f projection = Eigen::Map<const Eigen::Matrix4f>(camera.projection);
    const Eigen::Vector3f p = (view * center.homogeneous()).head<3>();
    const Eigen::Vector3f e = view.topLeftCorner<3, 3>() * major;
    const Eigen::Vector3f f = view.topLeftCorner<3, 3>() * minor;
    std::vector<bool> mask(std::size_t(width) * height, false);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            Eigen::Vector3f o, d;
            pixelRay(camera, width, height, x, y, o, d);
            Eigen::Matrix3f system;
            system << e, f, -d; // [E F −v]·(x, y, t)ᵀ = o − p
            const Eigen::Vector3f xyt = system.fullPivLu().solve(o - p);
            const Eigen::Vector4f clip = projection * (o + xyt.z() * d).homogeneous();
            const bool inRange = clip.w() > 0 && std::fabs(clip.z() / clip.w()) <= 1.0f;
            mask[std::size_t(y) * width + x] = inRange && xyt.head<2>().squaredNorm() <= 1.0f;
        }
    return mask;
}

Steps luminanceSteps(const Frame &frame, const std::vector<bool> &mask)
{
    std::vector<float> steps;
    for (int y = 0; y + 1 < frame.height; ++y)
        for (int x = 0; x + 1 < frame.width; ++x) {
            const std::size_t i = std::size_t(y) * frame.width + x;
            if (!mask[i])
                continue;
            const float l = frame.luminance(x, y);
            if (mask[i + 1])
                steps.push_back(std::fabs(frame.luminance(x + 1, y) - l));
            if (mask[i + frame.width])
                steps.push_back(std::fabs(frame.luminance(x, y + 1) - l));
        }
    if (steps.empty())
        return Steps{0, 0};
    std::sort(steps.begin(), steps.end());
    return Steps{steps.back(), steps[std::size_t(0.99 * (steps.size() - 1))]};
}

} // namespace test
} // namespace splat
