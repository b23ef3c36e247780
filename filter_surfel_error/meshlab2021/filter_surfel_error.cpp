#include "filter_surfel_error.h"

#include <common/mlexception.h>

#include "../surfel_error_layer.h"

namespace sef = surfel_error_filter;

FilterSurfelErrorPlugin::FilterSurfelErrorPlugin()
{
    typeList = {FP_SURFEL_APPROXIMATION_ERROR};
    for (ActionIDType t : types())
        actionList.push_back(new QAction(filterName(t), this));
}

QString FilterSurfelErrorPlugin::pluginName() const { return sef::PluginName(); }

QString FilterSurfelErrorPlugin::filterName(ActionIDType filter) const
{
    return filter == FP_SURFEL_APPROXIMATION_ERROR ? sef::FilterName() : QString();
}

// pymeshlab's name, in its get_*_measure family of filters that log figures.
QString FilterSurfelErrorPlugin::pythonFilterName(ActionIDType filter) const
{
    return filter == FP_SURFEL_APPROXIMATION_ERROR ? "get_surfel_approximation_error" : QString();
}

QString FilterSurfelErrorPlugin::filterInfo(ActionIDType filter) const
{
    return filter == FP_SURFEL_APPROXIMATION_ERROR ? sef::FilterInfo() : QString();
}

FilterPlugin::FilterClass FilterSurfelErrorPlugin::getClass(const QAction *) const
{
    return FilterClass(FilterPlugin::PointSet | FilterPlugin::Measure);
}

FilterPlugin::FilterArity FilterSurfelErrorPlugin::filterArity(const QAction *) const { return FIXED; }

// The metric runs on the CPU alone.
bool FilterSurfelErrorPlugin::requiresGLContext(const QAction *) const { return false; }

// Normals are always allocated in CMeshO; whether they mean anything is checked at run time.
int FilterSurfelErrorPlugin::getPreConditions(const QAction *) const { return MeshModel::MM_NONE; }

int FilterSurfelErrorPlugin::postCondition(const QAction *) const
{
    return MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR;
}

RichParameterList FilterSurfelErrorPlugin::initParameterList(const QAction *, const MeshDocument &md)
{
    RichParameterList par;
    sef::AddParameters(md, par, [&md](const sef::LayerParameter &p, int id) {
        return RichMesh(p.name, id, &md, p.label, p.help);
    });
    return par;
}

std::map<std::string, QVariant> FilterSurfelErrorPlugin::applyFilter(const QAction *filter, const RichParameterList &par,
                                                                     MeshDocument &md, unsigned int &,
                                                                     vcg::CallBackPos *cb)
{
    if (ID(filter) != FP_SURFEL_APPROXIMATION_ERROR) wrongActionCalled(filter);
    const sef::MeasureOutcome outcome = sef::Measure(md.getMesh(par.getMeshId(sef::kOriginalLayer.name)),
                                                     md.getMesh(par.getMeshId(sef::kSimplifiedLayer.name)), par, cb);
    for (const sef::LogLine &line : outcome.log)
        log(line.warning ? GLLogStream::WARNING : GLLogStream::FILTER, line.text.toStdString());
    if (!outcome.error.isEmpty()) throw MLException("Surfel approximation error failed: " + outcome.error);
    return {};
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterSurfelErrorPlugin)
