// splat_render: renders a point set (PLY or .surfel) or a triangle mesh offscreen to a PNG,
// with the camera given on the command line; optionally writes the depth and coverage mask.

#include "ellipse_splat_renderer.h"
#include "offscreen_gl.h"
#include "orbit_camera.h"
#include "point_set_file.h"

#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFile>
#include <QGuiApplication>

#include <Eigen/Dense>

#include <cstdio>
#include <iostream>
#include <stdexcept>

namespace {

const std::uint8_t kDefaultColor[4] = {192, 192, 192, 255};

enum class Mode { ThreePass, OnePass, Points, Mesh };

struct Options
{
    QString input, output, depthOutput, maskOutput;
    Mode mode = Mode::ThreePass;
    bool flatMesh = false;
    int width = 800, height = 600, benchmarkFrames = 0, neighbours = splat::kDefaultSplatNeighbours;
    splat::CameraSetup camera;
    splat::SplatSettings splats;
    float background[4] = {1, 1, 1, 1};
};

std::vector<float> parseNumbers(const QString &text, int count, const char *what)
{
    const QStringList parts = text.split(',');
    std::vector<float> values;
    bool ok = parts.size() == count;
    for (const QString &part : parts)
        values.push_back(part.toFloat(&ok ? &ok : nullptr));
    if (!ok)
        throw std::invalid_argument(std::string(what) + " needs " + std::to_string(count) + " comma-separated numbers");
    return values;
}

Options parseOptions(const QCoreApplication &app)
{
    QCommandLineParser parser;
    parser.setApplicationDescription("Renders a point set with elliptical splats (or points, or a mesh) to a PNG.");
    parser.addHelpOption();
    parser.addPositionalArgument("input", "PLY point set with normals, .surfel file, or PLY mesh (mode mesh)");
    const QCommandLineOption output({"o", "output"}, "PNG image to write.", "file");
    const QCommandLineOption mode("mode", "threepass (default), onepass, points or mesh.", "mode", "threepass");
    const QCommandLineOption flat("flat", "Mesh mode: flat shading (default: Phong, interpolated normals).");
    const QCommandLineOption width("width", "Image width in pixels.", "px", "800");
    const QCommandLineOption height("height", "Image height in pixels.", "px", "600");
    const QCommandLineOption azimuth("azimuth", "Camera azimuth about +Y in degrees (0: camera on +Z).", "deg", "0");
    const QCommandLineOption elevation("elevation", "Camera elevation in degrees.", "deg", "0");
    const QCommandLineOption viewDir("view-dir", "View direction x,y,z (overrides azimuth/elevation).", "x,y,z");
    const QCommandLineOption fov("fov", "Vertical field of view in degrees.", "deg", "30");
    const QCommandLineOption zoom("zoom", "Magnification; 1 frames the bounding sphere.", "factor", "1");
    const QCommandLineOption scale("splat-scale", "Multiplies every splat's semi-axes.", "factor", "1");
    const QCommandLineOption epsilon("depth-offset", "Blending depth tolerance eps, in splat major semi-axes.",
                                     "factor", "1");
    const QCommandLineOption neighbours("neighbours", "k for circular splats of files without ellipses/radii.", "k",
                                        QString::number(splat::kDefaultSplatNeighbours));
    const QCommandLineOption noVisibility("no-visibility-pass", "Three-pass mode without pass 1 (for comparison).");
    const QCommandLineOption noCull("no-cull", "Keep splats whose normal faces away from the camera.");
    const QCommandLineOption pointSize("point-size", "Points mode: point size in pixels.", "px", "3");
    const QCommandLineOption background("background", "Background colour r,g,b in 0..255.", "r,g,b", "255,255,255");
    const QCommandLineOption depthOut("depth-out", "Write the eye-space depth (0 = background) as PFM.", "file");
    const QCommandLineOption maskOut("mask-out", "Write the coverage mask (255 = drawn) as PNG.", "file");
    const QCommandLineOption bench("bench", "Render N more frames and print the mean time per frame.", "N", "0");
    parser.addOptions({output, mode, flat, width, height, azimuth, elevation, viewDir, fov, zoom, scale, epsilon,
                       neighbours, noVisibility, noCull, pointSize, background, depthOut, maskOut, bench});
    parser.process(app);

    if (parser.positionalArguments().size() != 1 || !parser.isSet(output))
        parser.showHelp(1);
    Options o;
    o.input = parser.positionalArguments().front();
    o.output = parser.value(output);
    o.depthOutput = parser.value(depthOut);
    o.maskOutput = parser.value(maskOut);
    const QString modeName = parser.value(mode);
    if (modeName == "threepass")
        o.mode = Mode::ThreePass;
    else if (modeName == "onepass")
        o.mode = Mode::OnePass;
    else if (modeName == "points")
        o.mode = Mode::Points;
    else if (modeName == "mesh")
        o.mode = Mode::Mesh;
    else
        throw std::invalid_argument("unknown mode " + modeName.toStdString());
    o.flatMesh = parser.isSet(flat);
    o.width = parser.value(width).toInt();
    o.height = parser.value(height).toInt();
    if (o.width <= 0 || o.height <= 0)
        throw std::invalid_argument("image size must be positive");
    if (parser.isSet(viewDir)) {
        const std::vector<float> d = parseNumbers(parser.value(viewDir), 3, "--view-dir");
        std::copy(d.begin(), d.end(), o.camera.viewDirection);
    } else {
        splat::viewDirectionFromAngles(parser.value(azimuth).toFloat(), parser.value(elevation).toFloat(),
                                       o.camera.viewDirection);
    }
    o.camera.fovYDegrees = parser.value(fov).toFloat();
    o.camera.zoom = parser.value(zoom).toFloat();
    o.camera.aspect = float(o.width) / float(o.height);
    o.splats.mode = o.mode == Mode::OnePass ? splat::SplatMode::OnePassOpaque
                    : o.mode == Mode::Points ? splat::SplatMode::Points
                                             : splat::SplatMode::ThreePass;
    o.splats.splatScale = parser.value(scale).toFloat();
    o.splats.depthOffsetFactor = parser.value(epsilon).toFloat();
    o.splats.visibilityPass = !parser.isSet(noVisibility);
    o.splats.cullBackFaces = !parser.isSet(noCull);
    o.splats.pointSize = parser.value(pointSize).toFloat();
    o.neighbours = parser.value(neighbours).toInt();
    o.benchmarkFrames = parser.value(bench).toInt();
    const std::vector<float> rgb = parseNumbers(parser.value(background), 3, "--background");
    for (int c = 0; c < 3; ++c)
        o.background[c] = rgb[c] / 255.0f;
    return o;
}

// Area-weighted vertex normals, for meshes stored without them.
std::vector<float> vertexNormalsOf(const splat::PointSetFile &mesh)
{
    const std::vector<float> &p = mesh.surfels.positions;
    std::vector<float> normals(p.size(), 0.0f);
    for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
        const unsigned *v = &mesh.triangles[t];
        const Eigen::Vector3f a(&p[3 * v[0]]), b(&p[3 * v[1]]), c(&p[3 * v[2]]);
        const Eigen::Vector3f areaNormal = (b - a).cross(c - a);
        for (int k = 0; k < 3; ++k)
            Eigen::Map<Eigen::Vector3f>(&normals[3 * v[k]]) += areaNormal;
    }
    return normals;
}

// Frames the usable positions (splat::isUsableVector): a NaN or 3e38 must not move the camera.
void frameModel(const std::vector<float> &positions, splat::CameraSetup &camera)
{
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e30f), hi = Eigen::Vector3f::Constant(-1e30f);
    for (std::size_t i = 0; i + 2 < positions.size(); i += 3) {
        if (!splat::isUsableVector(&positions[i]))
            continue;
        lo = lo.cwiseMin(Eigen::Vector3f(&positions[i]));
        hi = hi.cwiseMax(Eigen::Vector3f(&positions[i]));
    }
    Eigen::Map<Eigen::Vector3f>(camera.center) = (lo + hi) / 2;
    camera.radius = std::max((hi - lo).norm() / 2, 1e-6f);
}

void writeDepth(const QString &path, const splat::RenderTarget &target, const splat::Camera &camera)
{
    std::vector<float> depth = target.readDepth(); // bottom row first, as PFM stores it
    for (float &d : depth)
        d = d < 1.0f ? splat::eyeDistance(camera, d) : 0.0f;
    QFile file(path);
    if (!file.open(QIODevice::WriteOnly))
        throw std::runtime_error("cannot write " + path.toStdString());
    file.write(QString("Pf\n%1 %2\n-1\n").arg(target.width()).arg(target.height()).toLatin1()); // -1: little endian
    file.write(reinterpret_cast<const char *>(depth.data()), qint64(depth.size() * sizeof(float)));
}

void writeMask(const QString &path, const splat::RenderTarget &target)
{
    const std::vector<float> depth = target.readDepth();
    QImage mask(target.width(), target.height(), QImage::Format_Grayscale8);
    for (int y = 0; y < target.height(); ++y)
        for (int x = 0; x < target.width(); ++x)
            mask.scanLine(target.height() - 1 - y)[x] = depth[std::size_t(y) * target.width() + x] < 1.0f ? 255 : 0;
    if (!mask.save(path))
        throw std::runtime_error("cannot write " + path.toStdString());
}

// Gives the surfels of a point set circular frames when the file has no ellipses (radius from the
// file when positive, else estimated from k neighbours), and drops the ones that cannot be drawn
// (splat::removeUnusableSurfels), saying how many on stderr.
void completeSplats(splat::PointSetFile &model, int neighbours, const std::string &name)
{
    if (!model.hasNormals)
        throw std::runtime_error(name + " has no normals: splats need oriented points");
    if (model.surfels.majorAxes.empty()) {
        std::vector<float> radii = model.radii;
        const bool allRadiiPositive =
            !radii.empty() && std::all_of(radii.begin(), radii.end(), [](float r) { return r > 0; });
        if (!allRadiiPositive) {
            QElapsedTimer timer;
            timer.start();
            const std::vector<float> spacing = splat::nearestNeighbourRadii(model.surfels.positions, neighbours);
            std::fprintf(stderr, "splat_render: splat sizes of %zu points from %d neighbours in %.2f s\n",
                         model.surfels.size(), neighbours, double(timer.nsecsElapsed()) / 1e9);
            radii.resize(spacing.size(), 0.0f);
            for (std::size_t i = 0; i < radii.size(); ++i)
                if (!(radii[i] > 0))
                    radii[i] = spacing[i];
        }
        splat::assignCircularFrames(model.surfels, radii);
    }
    const std::size_t skipped = splat::removeUnusableSurfels(model.surfels);
    if (skipped > 0)
        std::fprintf(stderr, "splat_render: skipped %zu of %zu points (non-finite or beyond %g coordinates, or zero normals)\n",
                     skipped, skipped + model.surfels.size(), double(splat::kMaxCoordinate));
    if (model.surfels.size() == 0)
        throw std::runtime_error(name + " holds no drawable points");
}

int run(const Options &o)
{
    splat::PointSetFile model = splat::readPointSetFile(o.input.toStdString());
    if (model.surfels.size() == 0)
        throw std::runtime_error(o.input.toStdString() + " holds no vertices");
    // The box of every usable position frames the model, also of the points no splat is drawn
    // for (bench/render appends zero-normal records to set the box).
    splat::CameraSetup cameraSetup = o.camera;
    frameModel(model.surfels.positions, cameraSetup);
    const splat::Camera camera = splat::frameBoundingSphere(cameraSetup);
    if (o.mode != Mode::Mesh)
        completeSplats(model, o.neighbours, o.input.toStdString());

    splat::OffscreenGl gl;
    splat::RenderTarget target(o.width, o.height);
    splat::Lighting lighting;
    std::function<void()> drawFrame;
    std::unique_ptr<splat::ShadedMeshRenderer> meshRenderer;
    std::unique_ptr<splat::EllipseSplatRenderer> splatRenderer;
    std::unique_ptr<splat::SplatCloud> cloud;
    if (o.mode == Mode::Mesh) {
        if (model.triangles.empty())
            throw std::runtime_error(o.input.toStdString() + " has no faces: mode mesh needs a triangle mesh");
        const std::vector<float> normals = model.hasNormals ? model.surfels.normals : vertexNormalsOf(model);
        meshRenderer.reset(new splat::ShadedMeshRenderer(model.surfels.positions, normals, model.surfels.colors,
                                                         model.triangles, kDefaultColor));
        drawFrame = [&] { meshRenderer->render(camera.modelView, camera.projection, lighting, o.flatMesh); };
    } else {
        splatRenderer.reset(new splat::EllipseSplatRenderer);
        cloud.reset(new splat::SplatCloud(model.surfels, kDefaultColor));
        splat::SplatDrawItem item{cloud.get(), {}};
        std::copy(camera.modelView, camera.modelView + 16, item.modelView);
        drawFrame = [&, item] {
            splatRenderer->render({item}, camera.projection, {0, 0, o.width, o.height}, lighting, o.splats);
        };
    }

    target.clear(o.background);
    drawFrame();
    glFinish();
    if (o.benchmarkFrames > 0) {
        QElapsedTimer timer;
        timer.start();
        for (int i = 0; i < o.benchmarkFrames; ++i) {
            target.clear(o.background);
            drawFrame();
        }
        glFinish();
        std::printf("%.2f ms/frame (%d frames, %zu points, %dx%d)\n", double(timer.nsecsElapsed()) / 1e6 / o.benchmarkFrames,
                    o.benchmarkFrames, model.surfels.size(), o.width, o.height);
    }
    if (glGetError() != GL_NO_ERROR)
        throw std::runtime_error("OpenGL reported an error while rendering");
    if (!target.readColor().convertToFormat(QImage::Format_RGB888).save(o.output))
        throw std::runtime_error("cannot write " + o.output.toStdString());
    if (!o.depthOutput.isEmpty())
        writeDepth(o.depthOutput, target, camera);
    if (!o.maskOutput.isEmpty())
        writeMask(o.maskOutput, target);
    return 0;
}

} // namespace

int main(int argc, char **argv)
{
    QGuiApplication app(argc, argv);
    try {
        return run(parseOptions(app));
    } catch (const std::exception &error) {
        std::cerr << "splat_render: " << error.what() << '\n';
        return 2;
    }
}
