#include "render_ellipsesplat.h"

namespace {

void logWarnings(MeshDocument &document, const splat::LogTexts &texts)
{
    for (const QString &text : texts)
        document.Log.Log(GLLogStream::WARNING, text);
}

} // namespace

EllipseSplatRenderPlugin::EllipseSplatRenderPlugin() : action(new QAction(splat::actionName(), this))
{
    action->setToolTip(splat::actionToolTip());
}

QString EllipseSplatRenderPlugin::pluginName() const { return splat::pluginName(); }

QList<QAction *> EllipseSplatRenderPlugin::actions() { return {action}; }

bool EllipseSplatRenderPlugin::isSupported() { return views.supported(); }

void EllipseSplatRenderPlugin::Init(QAction *, MeshDocument &document,
                                    MLSceneGLSharedDataContext::PerMeshRenderingDataMap &, GLArea *view)
{
    logWarnings(document, views.init(view));
}

void EllipseSplatRenderPlugin::Render(QAction *, MeshDocument &document,
                                      MLSceneGLSharedDataContext::PerMeshRenderingDataMap &, GLArea *view)
{
    logWarnings(document, views.render(document, view));
}

void EllipseSplatRenderPlugin::Finalize(QAction *, MeshDocument *, GLArea *view) { views.finalize(view); }

MESHLAB_PLUGIN_NAME_EXPORTER(EllipseSplatRenderPlugin)
