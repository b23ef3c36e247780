// Rendering tests of the ellipse splat renderer on Mesa llvmpipe (run under Xvfb): analytic
// spheres and single ellipses whose images are known, and each pass shown to matter; and the
// file and line that GlProgram reports for a shader that does not compile.

#include "gl_program.h"
#include "render_test_support.h"

#include <gtest/gtest.h>

#include <QGuiApplication>

#include <cmath>
#include <memory>

using namespace splat;
using namespace splat::test;

namespace {

const std::uint8_t kGray[4] = {200, 200, 200, 255};
const std::uint8_t kRed[4] = {230, 20, 20, 255};
const std::uint8_t kBlue[4] = {20, 20, 230, 255};
constexpr int kSize = 256;

class SplatRendering : public ::testing::Test
{
protected:
    void SetUp() override
    {
        renderer.reset(new EllipseSplatRenderer);
        sphereCloud.reset(new SplatCloud(sampleSphere(unitSphere, 4000, kGray), kGray));
        CameraSetup setup;
        setup.radius = 1.15f; // a margin around the unit sphere
        setup.viewDirection[0] = 0.3f; // an oblique view: no symmetry of the sampling helps
        setup.viewDirection[1] = -0.4f;
        setup.viewDirection[2] = -1.0f;
        camera = frameBoundingSphere(setup);
        analytic = castSphere(unitSphere, camera, kSize, kSize);
        interior = erode(analytic.inside, kSize, kSize, 3); // away from the silhouette
    }

    Frame render(const SplatSettings &settings, std::vector<const SplatCloud *> clouds = {})
    {
        if (clouds.empty())
            clouds = {sphereCloud.get()};
        return renderSplats(*renderer, clouds, camera, kSize, kSize, settings);
    }

    static SplatSettings onePass()
    {
        SplatSettings s;
        s.mode = SplatMode::OnePassOpaque;
        return s;
    }

    const Sphere unitSphere{Eigen::Vector3f::Zero(), 1.0f};
    std::unique_ptr<EllipseSplatRenderer> renderer;
    std::unique_ptr<SplatCloud> sphereCloud;
    Camera camera;
    AnalyticImage analytic;
    std::vector<bool> interior;
};

int uncoveredInside(const Frame &frame, const std::vector<bool> &mask)
{
    int holes = 0;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x)
            holes += mask[std::size_t(y) * frame.width + x] && !frame.covered(x, y);
    return holes;
}

} // namespace

TEST_F(SplatRendering, ThreePassCoversTheSilhouetteWithoutHoles)
{
    const Frame frame = render(SplatSettings());
    EXPECT_EQ(uncoveredInside(frame, interior), 0);
    // Nothing far outside: splats may overhang the silhouette by about one splat radius.
    const std::vector<bool> farOutside = [&] {
        std::vector<bool> outside(analytic.inside.size());
        for (std::size_t i = 0; i < outside.size(); ++i)
            outside[i] = !analytic.inside[i];
        return erode(outside, kSize, kSize, 12);
    }();
    int strayPixels = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            strayPixels += farOutside[std::size_t(y) * kSize + x] && frame.covered(x, y);
    EXPECT_EQ(strayPixels, 0);
}

TEST_F(SplatRendering, DepthMatchesTheAnalyticSphere)
{
    const Frame frame = render(SplatSettings());
    const int c = kSize / 2;
    ASSERT_TRUE(analytic.inside[std::size_t(c) * kSize + c]);
    const float centreError = eyeDistance(camera, frame.depthAt(c, c)) - analytic.distance[std::size_t(c) * kSize + c];
    EXPECT_LT(std::fabs(centreError), 0.005f) << "unit sphere, centre pixel";

    float largestError = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const std::size_t i = std::size_t(y) * kSize + x;
            if (interior[i] && frame.covered(x, y))
                largestError =
                    std::max(largestError, std::fabs(eyeDistance(camera, frame.depthAt(x, y)) - analytic.distance[i]));
        }
    RecordProperty("largest_depth_error", std::to_string(largestError));
    EXPECT_LT(largestError, 0.02f) << "tangent splats stay within a small fraction of the radius of the surface";
}

TEST_F(SplatRendering, ThreePassShadingIsSmoothWhereOnePassShowsSplats)
{
    const Steps blended = luminanceSteps(render(SplatSettings()), interior);
    const Steps opaque = luminanceSteps(render(onePass()), interior);
    std::cout << "luminance steps: three-pass largest " << blended.largest << " p99 " << blended.percentile99
              << "; one-pass largest " << opaque.largest << " p99 " << opaque.percentile99 << '\n';
    EXPECT_LT(blended.largest, 8.0f);
    EXPECT_GT(opaque.largest, 2.0f * blended.largest);
    EXPECT_GT(opaque.percentile99, blended.percentile99);
}

TEST_F(SplatRendering, WithoutDepthOffsetOnlyTheNearestSplatIsBlended)
{
    SplatSettings noOffset;
    noOffset.depthOffsetFactor = 0.0f;
    const Steps blended = luminanceSteps(render(SplatSettings()), interior);
    const Steps unblended = luminanceSteps(render(noOffset), interior);
    std::cout << "luminance steps: eps = 1 largest " << blended.largest << "; eps = 0 largest " << unblended.largest
              << '\n';
    EXPECT_GT(unblended.largest, 2.0f * blended.largest);
}

TEST_F(SplatRendering, VisibilityPassKeepsHiddenSurfacesOutOfTheBlend)
{
    // A red ball in front of a blue one, as two layers; 0.2 apart along the view axis.
    const Sphere front{Eigen::Vector3f(0, 0, 1.6f), 0.4f};
    SplatCloud red(sampleSphere(front, 3000, kRed), kRed);
    SplatCloud blue(sampleSphere(unitSphere, 4000, kBlue), kBlue);
    CameraSetup setup;
    setup.center[2] = 0.5f;
    setup.radius = 1.6f;
    camera = frameBoundingSphere(setup);
    const int c = kSize / 2;

    auto blueExcess = [&](const Frame &frame) { // lighting is grey, so blue above green is blue albedo
        const QRgb pixel = frame.color.pixel(c, c);
        return qBlue(pixel) - qGreen(pixel);
    };
    const Frame withVisibility = render(SplatSettings(), {&blue, &red});
    SplatSettings noVisibility;
    noVisibility.visibilityPass = false;
    const Frame withoutVisibility = render(noVisibility, {&blue, &red});
    EXPECT_GT(qRed(withVisibility.color.pixel(c, c)), 150);
    EXPECT_LE(blueExcess(withVisibility), 2);
    EXPECT_GT(blueExcess(withoutVisibility), 40) << "without pass 1 the hidden blue ball bleeds through";
}

TEST_F(SplatRendering, ResizedViewportsReallocateTheTargets)
{
    for (const int size : {kSize, 160, kSize}) {
        const AnalyticImage a = castSphere(unitSphere, camera, size, size);
        const Frame frame = renderSplats(*renderer, {sphereCloud.get()}, camera, size, size, SplatSettings());
        EXPECT_EQ(uncoveredInside(frame, erode(a.inside, size, size, 3)), 0) << size << " pixels";
    }
}

TEST_F(SplatRendering, PointsLeaveHolesSplatsClose)
{
    SplatSettings points;
    points.mode = SplatMode::Points;
    points.pointSize = 1.0f;
    const Frame frame = render(points);
    int interiorPixels = 0;
    for (bool inside : interior)
        interiorPixels += inside;
    EXPECT_GT(uncoveredInside(frame, interior), interiorPixels / 2);
}

TEST_F(SplatRendering, SplatsWithoutNormalsAreSkipped)
{
    SurfelArrays unoriented = sampleSphere(unitSphere, 500, kGray);
    std::fill(unoriented.normals.begin(), unoriented.normals.end(), 0.0f);
    SplatCloud cloud(unoriented, kGray);
    const Frame frame = render(SplatSettings(), {&cloud});
    EXPECT_EQ(uncoveredInside(frame, std::vector<bool>(analytic.inside.size(), true)),
              kSize * kSize); // nothing drawn
}

// A single tilted, elongated ellipse against the CPU ray caster, at sizes from small to
// larger than the viewport (beyond any point-sprite size limit) and crossing the near plane.
struct EllipseCase
{
    const char *name;
    float zoom;
    float depthShift; // moves the ellipse towards the camera
    float axisScale;  // of both semi-axes
    Eigen::Vector3f majorDirection;
};

// Names the case in test listings (ctest shows it instead of the raw bytes).
void PrintTo(const EllipseCase &c, std::ostream *out)
{
    *out << c.name;
}

const Eigen::Vector3f kTilted(0.8f, 0.3f, 0.5f);

class SingleEllipse : public ::testing::TestWithParam<EllipseCase>
{
};

TEST_P(SingleEllipse, FootprintMatchesTheRayCaster)
{
    EllipseSplatRenderer renderer;
    const Eigen::Vector3f center(0.1f, -0.05f, GetParam().depthShift);
    const Eigen::Vector3f major = GetParam().majorDirection.normalized() * 0.9f * GetParam().axisScale;
    const Eigen::Vector3f minor = major.cross(Eigen::Vector3f(0.2f, 0.3f, 1.0f)).normalized() * 0.35f * GetParam().axisScale;
    SurfelArrays one;
    one.positions.assign(center.data(), center.data() + 3);
    const Eigen::Vector3f normal = major.cross(minor).normalized();
    one.normals.assign(normal.data(), normal.data() + 3);
    one.majorAxes.assign(major.data(), major.data() + 3);
    one.minorAxes.assign(minor.data(), minor.data() + 3);
    SplatCloud cloud(one, kGray);

    CameraSetup setup;
    setup.zoom = GetParam().zoom;
    const Camera camera = frameBoundingSphere(setup);
    const std::vector<bool> expected = castEllipse(center, major, minor, camera, kSize, kSize);
    SplatSettings twoSided;
    twoSided.cullBackFaces = false; // the orientation of a lone splat is arbitrary
    for (SplatMode mode : {SplatMode::ThreePass, SplatMode::OnePassOpaque}) {
        twoSided.mode = mode;
        const Frame frame = renderSplats(renderer, {&cloud}, camera, kSize, kSize, twoSided);
        int expectedPixels = 0, mismatches = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const bool e = expected[std::size_t(y) * kSize + x];
                expectedPixels += e;
                mismatches += e != frame.covered(x, y);
            }
        ASSERT_GT(expectedPixels, 50);
        // Only pixels whose centre lies within rounding of the border may differ.
        EXPECT_LE(mismatches, std::max(2, expectedPixels / 500))
            << GetParam().name << (mode == SplatMode::ThreePass ? " three-pass" : " one-pass") << ": "
            << expectedPixels << " pixels expected";
    }
}

INSTANTIATE_TEST_SUITE_P(Sizes, SingleEllipse,
                         ::testing::Values(EllipseCase{"small", 0.3f, 0.0f, 1.0f, kTilted},
                                           EllipseCase{"framed", 1.0f, 0.0f, 1.0f, kTilted},
                                           EllipseCase{"larger_than_viewport", 4.0f, 0.0f, 1.0f, kTilted},
                                           EllipseCase{"crossing_near_plane", 1.0f, 1.3f, 1.0f, kTilted},
                                           // along the view axis, from beyond the near plane to behind the eye
                                           EllipseCase{"reaching_behind_the_eye", 1.0f, 2.5f, 4.0f,
                                                       Eigen::Vector3f(0.1f, 0.2f, 1.0f)}),
                         [](const ::testing::TestParamInfo<EllipseCase> &info) { return info.param.name; });

// The driver reports compile errors in the source string numbers of the #line directives that
// embed_shaders.cmake writes, and GlProgram says which file each number stands for.
TEST(GlProgram, CompileErrorsNameTheFileAndLine)
{
    const shaders::ShaderSource vertex{"#version 330\nvoid main() { gl_Position = vec4(0.0); }\n", "0: v.vert.glsl"};
    const shaders::ShaderSource fragment{"#version 330\n#line 1 1\nfloat one() { return 1.0; }\n#line 3 0\n"
                                         "out vec4 color;\nvoid main() { color = vec4(undeclared); }\n",
                                         "0: f.frag.glsl, 1: one.glsl"};
    try {
        GlProgram program("broken", vertex, fragment);
        FAIL() << "an undeclared identifier compiled";
    } catch (const std::runtime_error &error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("0: f.frag.glsl, 1: one.glsl"), std::string::npos) << message;
        EXPECT_NE(message.find("0:4"), std::string::npos) << message;
    }
}

int main(int argc, char **argv)
{
    QGuiApplication app(argc, argv);
    ::testing::InitGoogleTest(&argc, argv);
    OffscreenGl gl; // one context for every test
    return RUN_ALL_TESTS();
}
