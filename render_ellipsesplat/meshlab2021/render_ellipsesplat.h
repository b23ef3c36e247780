#pragma once
// MeshLab 2021.05+ render plugin (RenderPlugin; built against 2022.02 and 2025.07) "Ellipse
// Splatting" (Render > Shaders). A thin adapter: what every host shares is in
// ../splat_views.h; the GL renderer is ../ellipse_splat_renderer.h.

#include <GL/glew.h>
#include <common/plugins/interfaces/render_plugin.h>

#include "../splat_views.h"

class EllipseSplatRenderPlugin : public QObject, public RenderPlugin
{
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(RENDER_PLUGIN_IID)
    Q_INTERFACES(RenderPlugin)

public:
    EllipseSplatRenderPlugin();

    QString pluginName() const override;
    QList<QAction *> actions() override;
    bool isSupported() override;
    void init(QAction *, MeshDocument &, MLSceneGLSharedDataContext::PerMeshRenderingDataMap &, GLArea *) override;
    void render(QAction *, MeshDocument &, MLSceneGLSharedDataContext::PerMeshRenderingDataMap &, GLArea *) override;
    void finalize(QAction *, MeshDocument *, GLArea *) override;

private:
    void logWarnings(MeshDocument &document, const splat::LogTexts &texts);

    QAction *action;
    splat::SplatViews views;
};
