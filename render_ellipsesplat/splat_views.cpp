#include "splat_views.h"

#include "layer_surfels.h"
#include "splat_settings_panel.h"

#include <meshlab_glue/meshlab_document.h>

#include <common/GLExtensionsManager.h>
#include <meshlab/glarea.h>

#include <Eigen/Dense>

#include <QElapsedTimer>
#include <QMainWindow>
#include <QProgressBar>
#include <QStatusBar>

namespace splat {

namespace {

// MeshLab's default colour for layers without per-vertex colour.
const std::uint8_t kDefaultSplatColor[4] = {192, 192, 192, 255};

// The splats are lit like MeshLab lights meshes: with its light 0 (a headlight by default).
Lighting lightingOfCurrentView()
{
    Lighting lighting;
    float position[4], ambient[4], diffuse[4];
    glGetLightfv(GL_LIGHT0, GL_POSITION, position); // already in eye space
    glGetLightfv(GL_LIGHT0, GL_AMBIENT, ambient);
    glGetLightfv(GL_LIGHT0, GL_DIFFUSE, diffuse);
    if (position[0] != 0.0f || position[1] != 0.0f || position[2] != 0.0f)
        std::copy(position, position + 3, lighting.towardsLight);
    std::copy(ambient, ambient + 3, lighting.ambient);
    std::copy(diffuse, diffuse + 3, lighting.diffuse);
    return lighting;
}

// MeshLab's render interface has no progress callback, and the splat sizes of a raw
// cloud of millions of points take seconds: their progress goes to the main window's status
// bar (message and MeshLab's progress bar), repainted at once rather than through the event
// loop, which must not run inside a paint. Returns an empty callback outside a main window.
ProgressCallback statusBarProgress(GLArea *view, const QString &what)
{
    QMainWindow *window = qobject_cast<QMainWindow *>(view->window());
    if (window == nullptr)
        return nullptr;
    QStatusBar *statusBar = window->statusBar();
    QProgressBar *progressBar = statusBar->findChild<QProgressBar *>();
    auto shown = std::make_shared<QElapsedTimer>();
    return [statusBar, progressBar, what, shown](double fraction) {
        if (shown->isValid() && shown->elapsed() < 100 && fraction < 1.0)
            return; // a tenth of a second between repaints
        shown->start();
        const int percent = int(100 * fraction);
        statusBar->showMessage(percent < 100 ? QString("%1: %2 %").arg(what).arg(percent) : what + ": done", 5000);
        if (progressBar != nullptr) {
            progressBar->show();
            if (percent < 100)
                progressBar->setValue(percent);
            else
                progressBar->reset();
        }
        statusBar->repaint();
    };
}

} // namespace

QString pluginName()
{
    return "RenderEllipseSplat";
}

QString actionName()
{
    return "Ellipse Splatting";
}

QString actionToolTip()
{
    return "Perspective-correct elliptical splats blended in three passes (oriented point sets)";
}

SplatViews::SplatViews() = default;

// The panel's signal calls into this object: the panel goes first.
SplatViews::~SplatViews()
{
    delete panel.data();
}

LogTexts SplatViews::init(GLArea *view)
{
    isSupported = false;
    view->makeCurrent();
    GLExtensionsManager::initializeGLextensions_notThrowing(); // a failure shows in unsupportedReason()
    const std::string reason = unsupportedReason();
    if (!reason.empty())
        return {QString::fromStdString(reason)};
    ViewResources resources;
    try {
        resources.renderer.reset(new EllipseSplatRenderer);
    } catch (const std::exception &error) {
        return {QString("Ellipse Splatting: ") + error.what()};
    }
    views[view] = std::move(resources);
    isSupported = true;

    if (panel == nullptr) {
        panel = new SplatSettingsPanel(view->window());
        QObject::connect(panel, &SplatSettingsPanel::changed, panel, [this] {
            for (auto &entry : views)
                entry.first->update();
        });
        panel->move(view->mapToGlobal(QPoint(10, 10)));
    }
    panel->show();
    return {};
}

LogTexts SplatViews::render(MeshDocument &document, GLArea *view)
{
    LogTexts log;
    auto found = views.find(view);
    if (found == views.end() || view->mvc() == nullptr || panel == nullptr)
        return log;
    ViewResources &resources = found->second;
    MLSceneGLSharedDataContext *shared = view->mvc()->sharedDataContext();
    if (shared == nullptr)
        return log;

    Eigen::Matrix4f viewModelView, projection;
    glGetFloatv(GL_MODELVIEW_MATRIX, viewModelView.data());
    glGetFloatv(GL_PROJECTION_MATRIX, projection.data());
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);

    std::vector<SplatDrawItem> items;
    std::set<int> liveLayers;
    for (MeshModel *layerPointer : meshlab_glue::Layers(document)) {
        const MeshModel &layer = *layerPointer;
        liveLayers.insert(layer.id());
        if (!view->meshVisibilityMap[layer.id()])
            continue;
        const SplatCloud *cloud = nullptr;
        if (layer.cm.fn > 0)
            logOnce(layer, "is a triangle mesh: drawn as usual", log);
        else if (layer.cm.vn > 0 && !layerHasNormals(layer))
            logOnce(layer, "has no normals: drawn as usual (Filters > Normals > Compute normals for point sets)", log);
        else if (layer.cm.vn > 0)
            cloud = cloudOf(resources, layer, view, log);
        if (cloud == nullptr) {
            shared->setMeshTransformationMatrix(layer.id(), layer.cm.Tr);
            shared->draw(layer.id(), view->context());
            continue;
        }
        // vcg matrices are row-major; the layer's own transformation applies first.
        const Eigen::Matrix4f layerTransform = Eigen::Map<const Eigen::Matrix<float, 4, 4, Eigen::RowMajor>>(
            layer.cm.Tr.V());
        SplatDrawItem item{cloud, {}};
        Eigen::Map<Eigen::Matrix4f>(item.modelView) = viewModelView * layerTransform;
        items.push_back(item);
    }
    for (auto it = resources.clouds.begin(); it != resources.clouds.end();)
        it = liveLayers.count(it->first) ? std::next(it) : resources.clouds.erase(it);

    try {
        resources.renderer->render(items, projection.data(), {viewport[0], viewport[1], viewport[2], viewport[3]},
                                   lightingOfCurrentView(), panel->settings());
    } catch (const std::exception &error) {
        if (loggedMessages.insert({-1, error.what()}).second) // not about one layer: once per MeshLab run
            log.push_back(QString("Ellipse Splatting failed: ") + error.what());
    }
    return log;
}

void SplatViews::finalize(GLArea *view)
{
    auto found = views.find(view);
    if (found != views.end()) {
        view->makeCurrent(); // the GL objects must be deleted in their context
        views.erase(found);
    }
    if (views.empty() && panel != nullptr) {
        panel->close();
        panel->deleteLater();
        panel = nullptr;
    }
    loggedMessages.clear();
}

const SplatCloud *SplatViews::cloudOf(ViewResources &resources, const MeshModel &layer, GLArea *view, LogTexts &log)
{
    LayerSplatOptions options;
    options.neighbours = panel->neighbours();
    options.atFittedPositions = panel->atFittedPositions();
    const std::uint64_t fingerprint = layerFingerprint(layer, options);
    CachedCloud &cached = resources.clouds[layer.id()];
    if (!cached.cloud || cached.fingerprint != fingerprint) {
        std::size_t skipped = 0;
        const QString what = QString("Ellipse Splatting: splat sizes of layer '%1'").arg(layer.label());
        const SurfelArrays surfels = surfelsOfLayer(layer, options, skipped, statusBarProgress(view, what));
        view->makeCurrent(); // repainting the status bar may have made another GL context current
        if (skipped > 0)
            logOnce(layer,
                    QString("has %1 points that cannot be drawn (non-finite or beyond %2 coordinates, or zero normals): "
                            "skipped")
                        .arg(skipped)
                        .arg(double(kMaxCoordinate)),
                    log);
        cached.cloud.reset(new SplatCloud(surfels, kDefaultSplatColor));
        cached.fingerprint = fingerprint;
    }
    return cached.cloud.get();
}

void SplatViews::logOnce(const MeshModel &layer, const QString &message, LogTexts &log)
{
    if (loggedMessages.insert({layer.id(), message}).second)
        log.push_back(QString("Ellipse Splatting: layer '%1' %2").arg(layer.label(), message));
}

} // namespace splat
