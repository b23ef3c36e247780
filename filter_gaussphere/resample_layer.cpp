#include "resample_layer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <vcg_ext/gaussphere/resampling.h>
#include <vcg_ext/gaussphere/surfels/surfel_mesh.h>

namespace gs = vcg::gaussphere;

namespace gaussphere_filter {

QString PluginName() { return "FilterGaussSphere"; }

QString FilterName(ResamplingFilter filter) { return gs::FilterTitle(filter); }

namespace {

QString ReconstructionFilterInfo()
{
    return "Resampling of an oriented point set into fewer points meant for surface reconstruction "
           "(<i>Surface Reconstruction: Screened Poisson</i>), which assumes evenly spread samples.<br>"
           "The count is what the Gaussian sphere level gives (or the target), as in <i>Gaussian Sphere "
           "Feature-Sensitive Resampling</i>; the clusters are grown from single points by merging the "
           "neighbours that add the least to the normal error, the height above the merged plane and the "
           "merged cluster's extent, so the points spread evenly over flat parts and stay dense at creases "
           "and fine detail. Each cluster becomes one point (a surfel, with the same attributes as the "
           "feature-sensitive filter writes).<br>"
           "Reconstruct from the new layer unweighted (Confidence Flag off): at the same count Screened "
           "Poisson then comes closer to the original than from CGAL's hierarchy or grid simplification "
           "or MeshLab's Poisson disk sampling on most models (docs/results.md).<br>"
           "The input needs per-vertex normals (Filters &gt; Normals, Curvatures and Orientation &gt; "
           "Compute normals for point sets).";
}

} // namespace

QString FilterInfo(ResamplingFilter filter)
{
    if (filter == ResamplingFilter::ForReconstruction) return ReconstructionFilterInfo();
    return "Feature-sensitive resampling of an oriented point set into elliptical surfels.<br>"
           "Points are clustered by where their normals fall on a subdivided Gaussian sphere: "
           "labels spread between neighbours whose normals share a Gaussian triangle, one-point "
           "clusters rejoin their most similar neighbour, and elongated clusters are split until "
           "they are disc-like. Each cluster becomes one surfel, so the output is dense where "
           "the normals vary (edges, ridges, fine detail) and sparse on flat parts.<br>"
           "The result is a new layer <i>&lt;name&gt; resampled</i>, placed by the input's "
           "transformation matrix, with unit normals, per-vertex "
           "radius, quality = number of input points represented, and the per-vertex attributes "
           "<i>EllipseMajorAxis</i> and <i>EllipseMinorAxis</i> (semi-axis vectors), <i>SurfelFitOffset</i> "
           "(how far FitOffsets moved each surfel) and <i>SurfelBlendScale</i> where the blend of a surfel "
           "was narrowed (at creases). Save it as <i>.surfel</i> to keep them; PLY keeps position, "
           "normal and radius only (splats of a PLY are drawn at the fitted positions).<br>"
           "The input needs per-vertex normals (Filters &gt; Normals, Curvatures and Orientation &gt; "
           "Compute normals for point sets); points with a zero or invalid normal are skipped.<br><br>"
           "See: <br><i>Miao Y., Pajarola R., Feng J.</i><br>"
           "<b>\"Feature sensitive re-sampling of point set surfaces with Gaussian spheres\"</b><br>"
           "Science China Information Sciences, 2012.";
}

void AddParameters(ResamplingFilter filter, RichParameterList &par)
{
    for (const gs::ParameterSpec &spec : gs::ParameterTable()) {
        if (!gs::InDialog(spec, filter)) continue;
        switch (spec.kind) {
        case gs::ParameterKind::Int: par.addParam(RichInt(spec.name, int(spec.defaultValue), spec.label, spec.help)); break;
        case gs::ParameterKind::Float:
            par.addParam(RichFloat(spec.name, float(spec.defaultValue), spec.label, spec.help));
            break;
        case gs::ParameterKind::Bool: par.addParam(RichBool(spec.name, spec.defaultValue != 0, spec.label, spec.help)); break;
        }
    }
}

namespace {

/// The dialog's values of the table's parameters; the others keep their defaults.
gs::ResamplingParams ParamsFromDialog(ResamplingFilter filter, const RichParameterList &par)
{
    gs::ResamplingParams param;
    param.spreadEvenly = filter == ResamplingFilter::ForReconstruction;
    for (const gs::ParameterSpec &spec : gs::ParameterTable()) {
        if (!gs::InDialog(spec, filter) || spec.set == nullptr) continue;
        switch (spec.kind) {
        case gs::ParameterKind::Int: spec.set(param, par.getInt(spec.name)); break;
        case gs::ParameterKind::Float: spec.set(param, par.getFloat(spec.name)); break;
        case gs::ParameterKind::Bool: spec.set(param, par.getBool(spec.name) ? 1 : 0); break;
        }
    }
    return param;
}

/// Every input point coloured by its cluster (grey: skipped); Scatter spreads neighbouring
/// indices over distant hues.
void ColourByCluster(const gs::ResamplingResult &result, CMeshO &in)
{
    const int clusters = std::max(1, int(result.surfels.size()));
    for (size_t i = 0; i < in.vert.size(); ++i) {
        const int c = result.representative[i];
        in.vert[i].C() = c < 0 ? vcg::Color4b::Gray : vcg::Color4b::Scatter(std::min(clusters, 4096), c % 4096);
    }
}

ResampleOutcome Failure(const QString &error)
{
    ResampleOutcome outcome;
    outcome.error = error;
    return outcome;
}

} // namespace

ResampleOutcome ResampleCurrentLayer(ResamplingFilter filter, MeshDocument &md, const RichParameterList &par,
                                     vcg::CallBackPos *cb)
{
    const auto start = std::chrono::steady_clock::now();
    MeshModel *input = md.mm();
    if (input == nullptr || input->cm.vn == 0) return Failure("The current layer is empty: there are no points to resample.");
    CMeshO &in = input->cm;
    // MeshLab gives a layer read without normals zero normals: say what to do about it.
    const gs::UsablePointCounts counts = gs::CountUsablePoints(in);
    if (counts.usable == 0 && counts.badNormal == counts.Live())
        return Failure("The layer has no normals (all are zero or invalid). Compute them first with "
                       "Filters > Normals, Curvatures and Orientation > Compute normals for point sets.");
    const gs::ResamplingParams param = ParamsFromDialog(filter, par);
    const std::string invalid = param.Validate();
    if (!invalid.empty()) return Failure(QString::fromStdString(invalid) + ".");

    gs::ResamplingResult result;
    try {
        result = gs::ResamplePointSet(in, param, cb);
    } catch (const gs::ResamplingCancelled &) {
        return Failure("Resampling was cancelled.");
    } catch (const std::exception &e) {
        return Failure(QString("Cannot resample: %1.").arg(e.what()));
    }

    auto representative = vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<int>(in, gs::kRepresentativeAttribute);
    for (size_t i = 0; i < in.vert.size(); ++i) representative[i] = result.representative[i];
    if (par.getBool("ColorizeClusters")) {
        input->updateDataMask(MeshModel::MM_VERTCOLOR);
        ColourByCluster(result, in);
    }
    ResampleOutcome outcome;
    outcome.output = md.addNewMesh("", input->label() + " resampled", true);
    // The surfels are in the input's own coordinates: the new layer takes its placement too (a
    // layer moved or aligned in MeshLab keeps its vertices and holds the move in Tr).
    outcome.output->cm.Tr = in.Tr;
    outcome.output->updateDataMask(MeshModel::MM_VERTRADIUS | MeshModel::MM_VERTQUALITY);
    gs::WriteSurfels(result.surfels, outcome.output->cm);
    if (input->hasDataMask(MeshModel::MM_VERTCOLOR)) {
        outcome.output->updateDataMask(MeshModel::MM_VERTCOLOR);
        gs::ColourSurfelsByMembers(in, result.representative, outcome.output->cm);
    }
    outcome.log = RunLog(result.stats);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    outcome.log.push_back({false, Format("Gaussian sphere resampling: the whole filter took %.3f s, %.3f s of it around the "
                                         "algorithm (layers, attributes, log)",
                                         seconds, seconds - result.stats.TotalSeconds())});
    return outcome;
}

} // namespace gaussphere_filter
