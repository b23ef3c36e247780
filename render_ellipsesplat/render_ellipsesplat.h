#pragma once
// MeshLab render plugin "Ellipse Splatting" (Render > Shaders): draws every visible oriented
// point set as perspective-correct elliptical splats (EllipseSplatRenderer); triangle meshes
// and point sets without normals keep MeshLab's usual drawing.

#include <GL/glew.h>
#include <common/interfaces.h>

#include "ellipse_splat_renderer.h"

#include <map>
#include <memory>
#include <set>

class SplatSettingsPanel;

class EllipseSplatRenderPlugin : public QObject, public MeshRenderInterface
{
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(MESH_RENDER_INTERFACE_IID)
    Q_INTERFACES(MeshRenderInterface)

public:
    EllipseSplatRenderPlugin();
    ~EllipseSplatRenderPlugin() override;

    QString pluginName() const override;
    QList<QAction *> actions() override;
    bool isSupported() override { return supported; }
    void Init(QAction *, MeshDocument &, MLSceneGLSharedDataContext::PerMeshRenderingDataMap &, GLArea *) override;
    void Render(QAction *, MeshDocument &, MLSceneGLSharedDataContext::PerMeshRenderingDataMap &, GLArea *) override;
    void Finalize(QAction *, MeshDocument *, GLArea *) override;

private:
    struct CachedCloud
    {
        std::uint64_t fingerprint;
        std::unique_ptr<splat::SplatCloud> cloud;
    };
    // GL objects live in one context: each view (GLArea) that uses the plugin has its own.
    struct ViewResources
    {
        std::unique_ptr<splat::EllipseSplatRenderer> renderer;
        std::map<int, CachedCloud> clouds; // by layer id
    };

    const splat::SplatCloud *cloudOf(ViewResources &resources, MeshDocument &document, const MeshModel &layer,
                                     GLArea *view);
    void logOnce(MeshDocument &document, const MeshModel &layer, const QString &message);

    QAction *action;
    bool supported = false;
    std::map<GLArea *, ViewResources> views;
    SplatSettingsPanel *panel = nullptr;
    std::set<std::pair<int, QString>> loggedMessages; // (layer id, or -1 for the whole view; message) logged
};
