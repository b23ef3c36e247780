#include "filter_surfel_error.h"

#include "../surfel_error_layer.h"

namespace sef = surfel_error_filter;

FilterSurfelErrorPlugin::FilterSurfelErrorPlugin()
{
    typeList << FP_SURFEL_APPROXIMATION_ERROR;
    for (FilterIDType t : types())
        actionList << new QAction(filterName(t), this);
}

QString FilterSurfelErrorPlugin::pluginName() const { return sef::PluginName(); }

QString FilterSurfelErrorPlugin::filterName(FilterIDType filter) const
{
    return filter == FP_SURFEL_APPROXIMATION_ERROR ? sef::FilterName() : QString();
}

QString FilterSurfelErrorPlugin::filterInfo(FilterIDType filter) const
{
    return filter == FP_SURFEL_APPROXIMATION_ERROR ? sef::FilterInfo() : QString();
}

MeshFilterInterface::FilterClass FilterSurfelErrorPlugin::getClass(QAction *)
{
    return FilterClass(MeshFilterInterface::PointSet | MeshFilterInterface::Measure);
}

MeshFilterInterface::FILTER_ARITY FilterSurfelErrorPlugin::filterArity(QAction *) const { return FIXED; }

// Normals are always allocated in CMeshO; whether they mean anything is checked at run time.
int FilterSurfelErrorPlugin::getPreConditions(QAction *) const { return MeshModel::MM_NONE; }

int FilterSurfelErrorPlugin::postCondition(QAction *) const
{
    return MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR;
}

void FilterSurfelErrorPlugin::initParameterSet(QAction *, MeshDocument &md, RichParameterList &par)
{
    sef::AddParameters(md, par, [&md](const sef::LayerParameter &p, int id) {
        return RichMesh(p.name, md.getMesh(id), &md, p.label, p.help);
    });
}

bool FilterSurfelErrorPlugin::applyFilter(QAction *filter, MeshDocument &, const RichParameterList &par,
                                          vcg::CallBackPos *cb)
{
    if (ID(filter) != FP_SURFEL_APPROXIMATION_ERROR) return false;
    const sef::MeasureOutcome outcome = sef::Measure(par.getMesh(sef::kOriginalLayer.name),
                                                     par.getMesh(sef::kSimplifiedLayer.name), par, cb);
    for (const sef::LogLine &line : outcome.log)
        Log(line.warning ? GLLogStream::WARNING : GLLogStream::FILTER, "%s", qUtf8Printable(line.text));
    if (outcome.error.isEmpty()) return true;
    // meshlabserver does not print errorMsg(), only the log: say it in both.
    errorMessage = outcome.error;
    Log(GLLogStream::WARNING, "Surfel approximation error failed: %s", qUtf8Printable(outcome.error));
    return false;
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterSurfelErrorPlugin)
