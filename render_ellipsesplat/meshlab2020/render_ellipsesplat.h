#pragma once
// MeshLab 2020.09 render plugin (MeshRenderInterface) "Ellipse Splatting" (Render > Shaders).
// A thin adapter: what every host shares is in ../splat_views.h; the GL renderer is
// ../ellipse_splat_renderer.h.

#include <GL/glew.h>
#include <common/interfaces.h>

#include "../splat_views.h"

class EllipseSplatRenderPlugin : public QObject, public MeshRenderInterface
{
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(MESH_RENDER_INTERFACE_IID)
    Q_INTERFACES(MeshRenderInterface)

public:
    EllipseSplatRenderPlugin();

    QString pluginName() const override;
    QList<QAction *> actions() override;
    bool isSupported() override;
    void Init(QAction *, MeshDocument &, MLSceneGLSharedDataContext::PerMeshRenderingDataMap &, GLArea *) override;
    void Render(QAction *, MeshDocument &, MLSceneGLSharedDataContext::PerMeshRenderingDataMap &, GLArea *) override;
    void Finalize(QAction *, MeshDocument *, GLArea *) override;

private:
    QAction *action;
    splat::SplatViews views;
};
