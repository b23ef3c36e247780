// Splat sizes of raw clouds from the neighbour grid (nearestNeighbourRadii) against vcglib's
// kd-tree on the same points: the same radii, the same coverage once rendered.

#include "render_test_support.h"

#include <vcg/space/index/kdtree/kdtree.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace splat;
using namespace splat::test;

namespace {

const std::uint8_t kGray[4] = {200, 200, 200, 255};

// n random points near the unit sphere (radial noise `noise`), a clump of near-duplicates and a
// few far outliers, with outward normals: uneven sampling, unlike sampleSphere's spiral.
SurfelArrays randomCloud(int n, float noise, unsigned seed)
{
    std::mt19937 random(seed);
    std::normal_distribution<float> gaussian;
    std::uniform_real_distribution<float> uniform(-noise, noise);
    SurfelArrays s;
    for (int i = 0; i < n; ++i) {
        Eigen::Vector3f d(gaussian(random), gaussian(random), gaussian(random));
        d.normalize();
        if (i % 50 == 1) // a clump: a point very near the previous one
            d = Eigen::Map<const Eigen::Vector3f>(&s.normals[s.normals.size() - 3]) + Eigen::Vector3f::Constant(1e-5f);
        const Eigen::Vector3f p = d * (1 + uniform(random)) * (i % 5000 == 1 ? 4.0f : 1.0f);
        s.positions.insert(s.positions.end(), p.data(), p.data() + 3);
        s.normals.insert(s.normals.end(), d.data(), d.data() + 3);
    }
    return s;
}

// The radii as vcglib's kd-tree finds them: the k-th nearest of the k + 1 nearest, self included.
std::vector<float> kdTreeRadii(const std::vector<float> &positions, int k)
{
    const int count = int(positions.size() / 3);
    vcg::ConstDataWrapper<vcg::Point3f> points(reinterpret_cast<const vcg::Point3f *>(positions.data()), count);
    vcg::KdTree<float> tree(points);
    vcg::KdTree<float>::PriorityQueue queue;
    std::vector<float> radii(count);
    for (int i = 0; i < count; ++i) {
        tree.doQueryK(points[i], std::min(k + 1, count), queue);
        radii[i] = std::sqrt(queue.getTopWeight());
    }
    return radii;
}

TEST(SplatFrames, RadiiMatchTheKdTree)
{
    const SurfelArrays cloud = randomCloud(60000, 0.01f, 1);
    for (int k : {1, 8, 20}) {
        const std::vector<float> grid = nearestNeighbourRadii(cloud.positions, k);
        const std::vector<float> tree = kdTreeRadii(cloud.positions, k);
        ASSERT_EQ(grid.size(), tree.size());
        int differing = 0;
        for (std::size_t i = 0; i < grid.size(); ++i)
            differing += !(std::fabs(grid[i] - tree[i]) <= 1e-5f * tree[i] + 1e-9f);
        EXPECT_EQ(differing, 0) << "k = " << k;
    }
}

// Degenerate clouds: every point at one place, on a line, on a plane, on a regular grid (ties).
TEST(SplatFrames, DegenerateCloudsMatchTheKdTree)
{
    std::vector<std::vector<float>> clouds(4);
    for (int i = 0; i < 2000; ++i) {
        const float t = float(i) / 2000;
        clouds[0].insert(clouds[0].end(), {0.5f, -2.0f, 7.0f});
        clouds[1].insert(clouds[1].end(), {t, 2 * t, -t});
        clouds[2].insert(clouds[2].end(), {std::sin(37.0f * i), std::cos(91.0f * i), 0.0f});
        clouds[3].insert(clouds[3].end(), {float(i % 10), float(i / 10 % 10), float(i / 100)});
    }
    for (std::size_t c = 0; c < clouds.size(); ++c) {
        const std::vector<float> grid = nearestNeighbourRadii(clouds[c], 8);
        const std::vector<float> tree = kdTreeRadii(clouds[c], 8);
        for (std::size_t i = 0; i < grid.size(); ++i)
            ASSERT_NEAR(grid[i], tree[i], 1e-5f * tree[i] + 1e-9f) << "cloud " << c << ", point " << i;
    }
}

TEST(SplatFrames, FewerPointsThanNeighbours)
{
    const std::vector<float> three = {0, 0, 0, 1, 0, 0, 0, 3, 0};
    EXPECT_EQ(nearestNeighbourRadii(three, 8), (std::vector<float>{3, std::sqrt(10.0f), std::sqrt(10.0f)}));
    EXPECT_EQ(nearestNeighbourRadii({1, 2, 3}, 8), std::vector<float>{0}); // a lone point
    EXPECT_TRUE(nearestNeighbourRadii({}, 8).empty());
}

TEST(SplatFrames, ProgressGoesFromZeroToOne)
{
    const SurfelArrays cloud = randomCloud(200000, 0.01f, 2);
    std::vector<double> reported;
    nearestNeighbourRadii(cloud.positions, 8, [&](double fraction) { reported.push_back(fraction); });
    ASSERT_GE(reported.size(), 5u);
    EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
    EXPECT_GE(reported.front(), 0.0);
    EXPECT_EQ(reported.back(), 1.0);
}

// Rendered with the grid's radii and with the kd-tree's, the cloud covers the same pixels.
TEST(SplatFrames, CoverageMatchesTheKdTreeFrames)
{
    SurfelArrays grid = randomCloud(20000, 0.002f, 3);
    SurfelArrays tree = grid;
    assignCircularFrames(grid, nearestNeighbourRadii(grid.positions, kDefaultSplatNeighbours));
    assignCircularFrames(tree, kdTreeRadii(tree.positions, kDefaultSplatNeighbours));
    EllipseSplatRenderer renderer;
    const SplatCloud gridCloud(grid, kGray), treeCloud(tree, kGray);
    CameraSetup setup;
    setup.radius = 1.2f;
    const Camera camera = frameBoundingSphere(setup);
    const int size = 256;
    const Frame a = renderSplats(renderer, {&gridCloud}, camera, size, size, SplatSettings());
    const Frame b = renderSplats(renderer, {&treeCloud}, camera, size, size, SplatSettings());
    int coveredA = 0, coveredB = 0, differing = 0;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            coveredA += a.covered(x, y);
            coveredB += b.covered(x, y);
            differing += a.covered(x, y) != b.covered(x, y);
        }
    }
    EXPECT_GT(coveredA, size * size / 3); // the sphere fills most of the view
    EXPECT_LE(differing, coveredB / 1000); // radii equal to float rounding: at most a few edge pixels
}

} // namespace
