#include "filter_gaussphere.h"

#include <common/mlexception.h>

#include "../resample_layer.h"

namespace gf = gaussphere_filter;

FilterGaussSpherePlugin::FilterGaussSpherePlugin()
{
    typeList = {FP_GAUSSPHERE_RESAMPLING, FP_GAUSSPHERE_RECONSTRUCTION};
    for (ActionIDType t : types())
        actionList.push_back(new QAction(filterName(t), this));
}

QString FilterGaussSpherePlugin::pluginName() const { return gf::PluginName(); }

QString FilterGaussSpherePlugin::filterName(ActionIDType filter) const
{
    return gf::IsFilter(filter) ? gf::FilterName(gf::FilterOf(filter)) : QString();
}

// pymeshlab's name: the default would be the long display name turned into snake case.
QString FilterGaussSpherePlugin::pythonFilterName(ActionIDType filter) const
{
    if (!gf::IsFilter(filter)) return QString();
    return filter == FP_GAUSSPHERE_RESAMPLING ? "generate_gaussian_sphere_resampling"
                                              : "generate_gaussian_sphere_resampling_for_reconstruction";
}

QString FilterGaussSpherePlugin::filterInfo(ActionIDType filter) const
{
    return gf::IsFilter(filter) ? gf::FilterInfo(gf::FilterOf(filter)) : QString();
}

FilterPlugin::FilterClass FilterGaussSpherePlugin::getClass(const QAction *) const
{
    return FilterClass(FilterPlugin::PointSet | FilterPlugin::Remeshing);
}

FilterPlugin::FilterArity FilterGaussSpherePlugin::filterArity(const QAction *) const { return SINGLE_MESH; }

// The resampling runs on the CPU alone.
bool FilterGaussSpherePlugin::requiresGLContext(const QAction *) const { return false; }

// Normals are always allocated in CMeshO; whether they mean anything is checked at run time.
int FilterGaussSpherePlugin::getPreConditions(const QAction *) const { return MeshModel::MM_NONE; }

int FilterGaussSpherePlugin::postCondition(const QAction *) const { return MeshModel::MM_VERTCOLOR; }

RichParameterList FilterGaussSpherePlugin::initParameterList(const QAction *filter, const MeshModel &)
{
    RichParameterList par;
    gf::AddParameters(gf::FilterOf(ID(filter)), par);
    return par;
}

std::map<std::string, QVariant> FilterGaussSpherePlugin::applyFilter(const QAction *filter, const RichParameterList &par,
                                                                     MeshDocument &md, unsigned int &,
                                                                     vcg::CallBackPos *cb)
{
    if (!gf::IsFilter(ID(filter))) wrongActionCalled(filter);
    const gf::ResampleOutcome outcome = gf::ResampleCurrentLayer(gf::FilterOf(ID(filter)), md, par, cb);
    if (!outcome.error.isEmpty()) throw MLException("Gaussian sphere resampling failed: " + outcome.error);
    for (const gf::LogLine &line : outcome.log)
        log(line.warning ? GLLogStream::WARNING : GLLogStream::FILTER, line.text);
    return {};
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterGaussSpherePlugin)
