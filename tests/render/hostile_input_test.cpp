// Points that cannot be drawn (NaN or infinite coordinates, coordinates near 3e38, zero
// normals, broken ellipse axes) are kept out of the neighbour search and skipped, and the rest
// is drawn: by the library (nearestNeighbourRadii, removeUnusableSurfels) and by the
// splat_render tool, which also refuses empty files with a message rather than crashing.

#include "render_test_support.h"

#include <gtest/gtest.h>

#include <QImage>
#include <QProcess>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>

using namespace splat;
using namespace splat::test;

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();
const std::uint8_t kGray[4] = {200, 200, 200, 255};

struct HostilePoint
{
    float position[3];
    float normal[3];
};

// One of each kind of point that cannot be drawn.
const std::vector<HostilePoint> kHostile = {
    {{kNaN, 0, 0}, {0, 0, 1}},         {{0, kInf, 0}, {0, 0, 1}},      {{0, 0, -kInf}, {0, 0, 1}},
    {{3e38f, 3e38f, 3e38f}, {0, 0, 1}}, {{-3e38f, 1, 1}, {0, 0, 1}},   {{0.3f, 0.3f, 0.3f}, {kNaN, 0, 1}},
    {{0.3f, 0.3f, 0.3f}, {0, kInf, 0}}, {{0.3f, 0.3f, 0.3f}, {0, 0, 0}}, {{0.2f, 0.1f, 0.3f}, {3e38f, 0, 0}},
};

// `clean` with the hostile points interleaved every `stride` surfels (no axes yet).
SurfelArrays withHostilePoints(const SurfelArrays &clean, std::size_t stride)
{
    SurfelArrays mixed;
    std::size_t next = 0;
    for (std::size_t i = 0; i < clean.size(); ++i) {
        if (i % stride == 0 && next < kHostile.size()) {
            const HostilePoint &h = kHostile[next++];
            mixed.positions.insert(mixed.positions.end(), h.position, h.position + 3);
            mixed.normals.insert(mixed.normals.end(), h.normal, h.normal + 3);
            mixed.colors.insert(mixed.colors.end(), {1, 2, 3, 4});
        }
        mixed.positions.insert(mixed.positions.end(), &clean.positions[3 * i], &clean.positions[3 * i] + 3);
        mixed.normals.insert(mixed.normals.end(), &clean.normals[3 * i], &clean.normals[3 * i] + 3);
        mixed.colors.insert(mixed.colors.end(), &clean.colors[4 * i], &clean.colors[4 * i] + 4);
    }
    return mixed;
}

int coveredPixels(const Frame &frame)
{
    int covered = 0;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x)
            covered += frame.covered(x, y);
    return covered;
}

TEST(HostileInput, UnusablePositionsStayOutOfTheNeighbourSearch)
{
    const SurfelArrays clean = sampleSphere({Eigen::Vector3f::Zero(), 1.0f}, 3000, kGray);
    const SurfelArrays mixed = withHostilePoints(clean, 200);
    const std::vector<float> cleanRadii = nearestNeighbourRadii(clean.positions, 8);
    const std::vector<float> mixedRadii = nearestNeighbourRadii(mixed.positions, 8);
    std::size_t c = 0, unusable = 0;
    for (std::size_t i = 0; i < mixed.size(); ++i) {
        if (!isUsableVector(&mixed.positions[3 * i])) {
            EXPECT_EQ(mixedRadii[i], 0.0f) << "point " << i;
            ++unusable;
            continue;
        }
        // The usable hostile points (bad normals only) sit inside the sphere, away from the surface.
        if (mixed.colors[4 * i] == 1)
            continue;
        EXPECT_FLOAT_EQ(mixedRadii[i], cleanRadii[c]) << "point " << i;
        ++c;
    }
    EXPECT_EQ(unusable, 5u);
    EXPECT_EQ(c, clean.size());
}

TEST(HostileInput, RemoveUnusableSurfelsKeepsTheRestInOrder)
{
    const SurfelArrays clean = sampleSphere({Eigen::Vector3f::Zero(), 1.0f}, 1000, kGray);
    SurfelArrays mixed = withHostilePoints(clean, 100);
    assignCircularFrames(mixed, nearestNeighbourRadii(mixed.positions, 8));
    // Broken axes on otherwise good surfels.
    mixed.majorAxes[3 * 10] = kNaN;
    mixed.minorAxes[3 * 20 + 1] = -kInf;
    mixed.majorAxes[3 * 30 + 2] = 2e38f;
    EXPECT_EQ(removeUnusableSurfels(mixed), kHostile.size() + 3);
    ASSERT_EQ(mixed.size(), clean.size() - 3);
    ASSERT_TRUE(mixed.hasColors());
    EXPECT_EQ(mixed.normals.size(), 3 * mixed.size());
    EXPECT_EQ(mixed.majorAxes.size(), 3 * mixed.size());
    EXPECT_EQ(mixed.minorAxes.size(), 3 * mixed.size());
    for (std::size_t i = 0; i < mixed.size(); ++i) {
        EXPECT_TRUE(isUsableVector(&mixed.positions[3 * i]) && isUsableVector(&mixed.majorAxes[3 * i]) &&
                    isUsableVector(&mixed.minorAxes[3 * i]));
        EXPECT_EQ(mixed.colors[4 * i], kGray[0]);
        EXPECT_NEAR(Eigen::Map<const Eigen::Vector3f>(&mixed.normals[3 * i]).norm(), 1.0f, 1e-5f);
    }
    SurfelArrays empty;
    EXPECT_EQ(removeUnusableSurfels(empty), 0u);
}

TEST(HostileInput, TheUsableSplatsAreDrawnAsWithoutTheOthers)
{
    const SurfelArrays clean = sampleSphere({Eigen::Vector3f::Zero(), 1.0f}, 4000, kGray);
    SurfelArrays mixed = withHostilePoints(clean, 300);
    assignCircularFrames(mixed, nearestNeighbourRadii(mixed.positions, kDefaultSplatNeighbours));
    removeUnusableSurfels(mixed);
    EllipseSplatRenderer renderer;
    const SplatCloud cleanCloud(clean, kGray), mixedCloud(mixed, kGray), emptyCloud(SurfelArrays(), kGray);
    CameraSetup setup;
    setup.radius = 1.2f;
    const Camera camera = frameBoundingSphere(setup);
    const Frame expected = renderSplats(renderer, {&cleanCloud}, camera, 200, 200, SplatSettings());
    const Frame actual = renderSplats(renderer, {&mixedCloud}, camera, 200, 200, SplatSettings());
    EXPECT_GT(coveredPixels(expected), 200 * 200 / 3);
    EXPECT_EQ(coveredPixels(actual), coveredPixels(expected));
    EXPECT_EQ(coveredPixels(renderSplats(renderer, {&emptyCloud}, camera, 200, 200, SplatSettings())), 0);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// A binary PLY of oriented points (no radii, no axes: splat_render estimates the sizes), then the
// header lines `elements` declares and their records' bytes `records`.
std::string writePly(const std::string &name, const std::vector<HostilePoint> &points,
                     const std::string &elements = "", const std::string &records = "")
{
    const std::string path = testing::TempDir() + name;
    std::ofstream out(path, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << points.size()
        << "\nproperty float x\nproperty float y\nproperty float z\n"
           "property float nx\nproperty float ny\nproperty float nz\n"
        << elements << "end_header\n";
    out.write(reinterpret_cast<const char *>(points.data()), std::streamsize(points.size() * sizeof(HostilePoint)));
    out << records;
    return path;
}

struct ToolRun
{
    int exitCode;
    QString errors;
    int covered;
};

ToolRun runSplatRender(const std::string &input)
{
    const QString mask = QString::fromStdString(input + ".mask.png");
    QProcess tool;
    tool.start(SPLAT_RENDER_PATH, {QString::fromStdString(input), "-o", QString::fromStdString(input + ".png"),
                                   "--mask-out", mask, "--width", "160", "--height", "120"});
    EXPECT_TRUE(tool.waitForFinished(60000));
    EXPECT_EQ(tool.exitStatus(), QProcess::NormalExit) << "splat_render crashed on " << input;
    ToolRun run{tool.exitCode(), QString::fromLocal8Bit(tool.readAllStandardError()), 0};
    const QImage image(mask);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            run.covered += qGray(image.pixel(x, y)) > 0;
    return run;
}

TEST(HostileInput, SplatRenderSkipsThePointsItCannotDrawAndDrawsTheRest)
{
    const SurfelArrays sphere = sampleSphere({Eigen::Vector3f::Zero(), 1.0f}, 3000, kGray);
    std::vector<HostilePoint> clean(sphere.size());
    for (std::size_t i = 0; i < sphere.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            clean[i].position[c] = sphere.positions[3 * i + c];
            clean[i].normal[c] = sphere.normals[3 * i + c];
        }
    std::vector<HostilePoint> mixed = clean;
    // The hostile points without a usable position first and last: none of them moves the camera.
    mixed.insert(mixed.begin(), kHostile.begin(), kHostile.begin() + 5);
    mixed.insert(mixed.end(), kHostile.begin() + 5, kHostile.end());
    const ToolRun cleanRun = runSplatRender(writePly("clean_sphere.ply", clean));
    const ToolRun mixedRun = runSplatRender(writePly("hostile_sphere.ply", mixed));
    EXPECT_EQ(cleanRun.exitCode, 0) << cleanRun.errors.toStdString();
    EXPECT_EQ(mixedRun.exitCode, 0) << mixedRun.errors.toStdString();
    EXPECT_TRUE(mixedRun.errors.contains(QString("skipped %1 of %2 points").arg(kHostile.size()).arg(mixed.size())))
        << mixedRun.errors.toStdString();
    EXPECT_GT(cleanRun.covered, 160 * 120 / 8); // the framed sphere: a disc of about 70 px across
    // The usable hostile points sit inside the sphere: the same box frames both.
    EXPECT_EQ(mixedRun.covered, cleanRun.covered);
}

TEST(HostileInput, SplatRenderRefusesFilesWithNothingToDraw)
{
    const ToolRun empty = runSplatRender(writePly("empty.ply", {}));
    EXPECT_EQ(empty.exitCode, 2);
    EXPECT_TRUE(empty.errors.contains("holds no vertices")) << empty.errors.toStdString();
    const ToolRun hostile = runSplatRender(writePly("all_hostile.ply", kHostile));
    EXPECT_EQ(hostile.exitCode, 2);
    EXPECT_TRUE(hostile.errors.contains("holds no drawable points")) << hostile.errors.toStdString();
}

TEST(HostileInput, SplatRenderRefusesListsPlylibWouldWritePast)
{
    const std::vector<HostilePoint> points(3, HostilePoint{{0, 0, 0}, {0, 0, 1}});
    // plylib skips an unread binary list through 512 bytes: 185 ints would write 740.
    const ToolRun skipped = runSplatRender(writePly("skipped_list.ply", points, "element extra 1\nproperty list uchar int data\n",
                                                    std::string(1, char(185)) + std::string(740, 'A')));
    EXPECT_NE(skipped.exitCode, 0);
    EXPECT_TRUE(skipped.errors.contains("list property 'data' of element 'extra' is not supported"))
        << skipped.errors.toStdString();
    // A face of 600 corners counted by an int would write past the reader's 512.
    std::string face(4, '\0');
    const std::int32_t corners = 600;
    std::memcpy(&face[0], &corners, 4);
    face += std::string(4 * 600, '\0');
    const ToolRun polygon = runSplatRender(
        writePly("long_face.ply", points, "element face 1\nproperty list int int vertex_indices\n", face));
    EXPECT_NE(polygon.exitCode, 0);
    EXPECT_TRUE(polygon.errors.contains("list property 'vertex_indices' of element 'face' is not supported"))
        << polygon.errors.toStdString();
}

TEST(HostileInput, SplatRenderRefusesHeadersPlylibReadsOtherwise)
{
    const auto write = [](const std::string &name, const std::string &bytes) {
        const std::string path = testing::TempDir() + name;
        std::ofstream(path, std::ios::binary) << bytes;
        return path;
    };
    // A NUL byte hides the format line from plylib's header text, not from its parse.
    const std::string body = std::string(12, '\0') + std::string(1, char(255)) + std::string(2040, 'A');
    const ToolRun nul = runSplatRender(write("nul_header.ply", std::string("ply\0\n", 5) +
        "format binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
        "property list uchar double pad\nend_header\n" + body));
    EXPECT_NE(nul.exitCode, 0);
    EXPECT_TRUE(nul.errors.contains("NUL byte")) << nul.errors.toStdString();
    // plylib reads the count of `element vertex` with atoi, of a missing token.
    const ToolRun countless = runSplatRender(write("countless.ply", "ply\nformat ascii 1.0\nelement vertex\n"
        "property float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n"));
    EXPECT_NE(countless.exitCode, 0);
    EXPECT_TRUE(countless.errors.contains("needs a name and a count of digits")) << countless.errors.toStdString();
}

} // namespace
