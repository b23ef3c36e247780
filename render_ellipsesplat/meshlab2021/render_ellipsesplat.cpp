#include "render_ellipsesplat.h"

#include <common/ml_document/mesh_document.h>

EllipseSplatRenderPlugin::EllipseSplatRenderPlugin() : action(new QAction(splat::actionName(), this))
{
    action->setToolTip(splat::actionToolTip());
}

QString EllipseSplatRenderPlugin::pluginName() const { return splat::pluginName(); }

QList<QAction *> EllipseSplatRenderPlugin::actions() { return {action}; }

bool EllipseSplatRenderPlugin::isSupported() { return views.supported(); }

void EllipseSplatRenderPlugin::init(QAction *, MeshDocument &document,
                                    MLSceneGLSharedDataContext::PerMeshRenderingDataMap &, GLArea *view)
{
    logWarnings(document, views.init(view));
}

void EllipseSplatRenderPlugin::render(QAction *, MeshDocument &document,
                                      MLSceneGLSharedDataContext::PerMeshRenderingDataMap &, GLArea *view)
{
    logWarnings(document, views.render(document, view));
}

void EllipseSplatRenderPlugin::finalize(QAction *, MeshDocument *, GLArea *view) { views.finalize(view); }

// MeshLab gives render plugins no log stream (it calls setLog for filters and decorations
// only): the document's is set before logging.
void EllipseSplatRenderPlugin::logWarnings(MeshDocument &document, const splat::LogTexts &texts)
{
    setLog(&document.Log);
    for (const QString &text : texts)
        log(GLLogStream::WARNING, text.toStdString());
}

MESHLAB_PLUGIN_NAME_EXPORTER(EllipseSplatRenderPlugin)
