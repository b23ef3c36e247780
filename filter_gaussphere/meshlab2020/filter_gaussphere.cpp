#include "filter_gaussphere.h"

#include "../resample_layer.h"

namespace gf = gaussphere_filter;

FilterGaussSpherePlugin::FilterGaussSpherePlugin()
{
    typeList << FP_GAUSSPHERE_RESAMPLING << FP_GAUSSPHERE_RECONSTRUCTION;
    for (FilterIDType t : types())
        actionList << new QAction(filterName(t), this);
}

QString FilterGaussSpherePlugin::pluginName() const { return gf::PluginName(); }

QString FilterGaussSpherePlugin::filterName(FilterIDType filter) const
{
    return gf::IsFilter(filter) ? gf::FilterName(gf::FilterOf(filter)) : QString();
}

QString FilterGaussSpherePlugin::filterInfo(FilterIDType filter) const
{
    return gf::IsFilter(filter) ? gf::FilterInfo(gf::FilterOf(filter)) : QString();
}

MeshFilterInterface::FilterClass FilterGaussSpherePlugin::getClass(QAction *)
{
    return FilterClass(MeshFilterInterface::PointSet | MeshFilterInterface::Remeshing);
}

MeshFilterInterface::FILTER_ARITY FilterGaussSpherePlugin::filterArity(QAction *) const { return SINGLE_MESH; }

// Normals are always allocated in CMeshO; whether they mean anything is checked at run time.
int FilterGaussSpherePlugin::getPreConditions(QAction *) const { return MeshModel::MM_NONE; }

int FilterGaussSpherePlugin::postCondition(QAction *) const { return MeshModel::MM_VERTCOLOR; }

void FilterGaussSpherePlugin::initParameterSet(QAction *filter, MeshModel &, RichParameterList &par)
{
    gf::AddParameters(gf::FilterOf(ID(filter)), par);
}

bool FilterGaussSpherePlugin::applyFilter(QAction *filter, MeshDocument &md, const RichParameterList &par,
                                          vcg::CallBackPos *cb)
{
    if (!gf::IsFilter(ID(filter))) return false;
    const gf::ResampleOutcome outcome = gf::ResampleCurrentLayer(gf::FilterOf(ID(filter)), md, par, cb);
    if (!outcome.error.isEmpty()) {
        // meshlabserver does not print errorMsg(), only the log: say it in both.
        errorMessage = outcome.error;
        Log(GLLogStream::WARNING, "Gaussian sphere resampling failed: %s", qUtf8Printable(outcome.error));
        return false;
    }
    for (const gf::LogLine &line : outcome.log)
        Log(line.warning ? GLLogStream::WARNING : GLLogStream::FILTER, "%s", line.text.c_str());
    return true;
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterGaussSpherePlugin)
