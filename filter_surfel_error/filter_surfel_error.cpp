#include "filter_surfel_error.h"

#include <QElapsedTimer>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <vcg_ext/surfel/surfel_attributes.h> // attribute names of docs/surfel_format.md
#include <vcg_ext/surfel_error/surfel_error.h>

namespace gs = vcg::gaussphere;

namespace {

/// Copies a per-vertex attribute into a plain array; false when the layer has none of that
/// name and type.
template <class T>
bool CopyPerVertexAttribute(CMeshO& m, const char* name, std::vector<T>& values)
{
    auto handle = vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<T>(m, name);
    if (!vcg::tri::Allocator<CMeshO>::IsValidHandle(m, handle))
        return false;
    values.resize(m.vert.size());
    for (size_t i = 0; i < m.vert.size(); ++i)
        values[i] = handle[i];
    return true;
}

bool HasSurfelIndex(MeshModel* layer)
{
    return vcg::tri::HasPerVertexAttribute(layer->cm, gs::kRepresentativeAttribute);
}

/// Live vertices whose normal is non-zero and finite; 0 means the layer has no normals.
int CountNormals(const CMeshO& m)
{
    int count = 0;
    for (const CVertexO& v : m.vert) {
        const double length2 = vcg::Point3d::Construct(v.cN()).SquaredNorm();
        if (!v.IsD() && length2 > 0 && std::isfinite(length2))
            ++count;
    }
    return count;
}

} // namespace

FilterSurfelErrorPlugin::FilterSurfelErrorPlugin()
{
    typeList << FP_SURFEL_APPROXIMATION_ERROR;
    for (FilterIDType t : types())
        actionList << new QAction(filterName(t), this);
}

QString FilterSurfelErrorPlugin::pluginName() const
{
    return "FilterSurfelError";
}

QString FilterSurfelErrorPlugin::filterName(FilterIDType filter) const
{
    switch (filter) {
    case FP_SURFEL_APPROXIMATION_ERROR:
        return "Surfel Approximation Error";
    default:
        return QString();
    }
}

QString FilterSurfelErrorPlugin::filterInfo(FilterIDType filter) const
{
    switch (filter) {
    case FP_SURFEL_APPROXIMATION_ERROR:
        return "Measures how well a simplified point set (surfels, e.g. the output of <i>Gaussian Sphere "
               "Feature-Sensitive Resampling</i>, or plain oriented points from any simplification) "
               "approximates the original oriented point set, with the figures of the Gaussian sphere "
               "resampling paper (section 5.2).<br>"
               "Each original point q is projected onto the surface defined by the simplified set with an "
               "MLS \"almost orthogonal\" projection: the k nearest surfels are blended with Gaussian "
               "weights "
               "sized by their ellipse axes (<i>EllipseMajorAxis</i>/<i>EllipseMinorAxis</i>), else by their "
               "radius, else by the local spacing (times <i>SurfelBlendScale</i> where the resampler "
               "narrowed it), and q is moved onto the plane through the weighted "
               "centroid with the blended normal until it stops moving. d(q) is the distance to that "
               "projection.<br>"
               "The log reports, over the original points: the RMS and maximum of d divided by the "
               "bounding box diagonal (D*rms, D*max) and their absolute values; the shape L2,1 error "
               "|n<sub>q</sub> - n'| against (a) the surfel that represents q (the <i>SurfelIndex</i> "
               "attribute left on the original layer by the resampling, else the nearest surfel) and "
               "(b) the blended normal at the projection; beside each maximum its 99.9th percentile.<br>"
               "d(q) is stored in the original layer's vertex quality: use <i>Colorize by vertex "
               "quality</i> for an error map, or tick the option below. Choosing the same layer twice "
               "gives the floor of the metric, the error of the projection itself.<br>"
               "Both layers need per-vertex normals; an original layer without normals gets the "
               "distances only.<br>"
               "Hostile input: original points with a non-finite position are not measured (quality 0), "
               "those with a zero or non-finite normal count for the distances only, and simplified "
               "points with a non-finite position or a zero or non-finite normal are ignored; the log "
               "counts each kind. The filter fails when nothing usable is left in a layer, and when a "
               "coordinate of a measured point or usable surfel exceeds 1e18 in magnitude: the spatial "
               "index works in single precision and its squared distances would overflow. Scale such "
               "layers down first (e.g. <i>Transform: Scale, Normalize</i>, by a power of two to keep "
               "the coordinates exact).<br><br>"
               "See: <br><i>Miao Y., Pajarola R., Feng J.</i><br>"
               "<b>\"Feature sensitive re-sampling of point set surfaces with Gaussian spheres\"</b><br>"
               "Science China Information Sciences, 2012.<br>"
               "<i>Alexa M., Adamson A.</i><br>"
               "<b>\"On normals and projection operators for surfaces defined by point sets\"</b><br>"
               "Symposium on Point-Based Graphics, 2004.";
    default:
        return QString();
    }
}

MeshFilterInterface::FilterClass FilterSurfelErrorPlugin::getClass(QAction*)
{
    return FilterClass(MeshFilterInterface::PointSet | MeshFilterInterface::Measure);
}

MeshFilterInterface::FILTER_ARITY FilterSurfelErrorPlugin::filterArity(QAction*) const
{
    return FIXED;
}

// Normals are always allocated in CMeshO; whether they mean anything is checked at run time.
int FilterSurfelErrorPlugin::getPreConditions(QAction*) const
{
    return MeshModel::MM_NONE;
}

int FilterSurfelErrorPlugin::postCondition(QAction*) const
{
    return MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR;
}

void FilterSurfelErrorPlugin::initParameterSet(QAction*, MeshDocument& md, RichParameterList& par)
{
    // Right after a resampling the current layer is its output and the input carries SurfelIndex.
    MeshModel* original = md.mm();
    for (MeshModel* layer : md.meshList)
        if (HasSurfelIndex(layer)) {
            original = layer;
            break;
        }
    MeshModel* simplified = original;
    if (md.mm() != original)
        simplified = md.mm();
    else
        for (MeshModel* layer : md.meshList)
            if (layer != original) {
                simplified = layer;
                break;
            }

    const vcg::gaussphere::metric::SurfelErrorParams defaults;
    par.addParam(
        RichMesh("OriginalMesh", original, &md, "Original point set",
                 "The original oriented point set S: every one of its points is measured. Its vertex quality "
                 "receives the distance to the simplified surface."));
    par.addParam(RichMesh(
        "SimplifiedMesh", simplified, &md, "Simplified point set",
        "The simplified point set S' (surfels, or plain oriented points) that defines the surface the "
        "original points are projected onto. Choose the original layer again to measure the floor of "
        "the metric."));
    par.addParam(RichBool(
        "UseSurfelIndex", true, "Own surfel from SurfelIndex",
        "For the L2,1 error against the surfel representing each point, use the original layer's "
        "<i>SurfelIndex</i> attribute (written by Gaussian Sphere Feature-Sensitive Resampling) when "
        "present. Untick it, or when the attribute refers to another simplified layer, to compare "
        "against the nearest surfel instead. Ignored when both layers are the same."));
    par.addParam(RichInt("NeighborCount", defaults.neighborCount, "Blended surfels (k)",
                         "Number of nearest surfels blended by the projection at each step."));
    par.addParam(RichFloat(
        "WidthFactor", float(defaults.widthFactor), "Gaussian width factor",
        "Width of each surfel's Gaussian weight, in units of its semi-axes (or radius, or local spacing "
        "for plain points). Larger values smooth more, which raises the floor of the metric on curved "
        "parts."));
    par.addParam(RichBool(
        "ColorizeByDistance", false, "Colour the original by distance",
        "Also colour the original layer's vertices by distance: blue for 0, red at the 99.9th "
        "percentile and above (the few larger values do not flatten the map). Otherwise only the vertex "
        "quality is written."));
}

bool FilterSurfelErrorPlugin::applyFilter(QAction* filter, MeshDocument& md, const RichParameterList& par,
                                          vcg::CallBackPos* cb)
{
    switch (ID(filter)) {
    case FP_SURFEL_APPROXIMATION_ERROR:
        return measure(md, par, cb);
    default:
        return false;
    }
}

// meshlabserver does not print errorMsg(), only the log: say it in both.
bool FilterSurfelErrorPlugin::fail(const QString& message)
{
    errorMessage = message;
    Log(GLLogStream::WARNING, "Surfel approximation error failed: %s", qUtf8Printable(message));
    return false;
}

bool FilterSurfelErrorPlugin::measure(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb)
{
    MeshModel* original = par.getMesh("OriginalMesh");
    MeshModel* simplified = par.getMesh("SimplifiedMesh");
    if (original == nullptr || simplified == nullptr)
        return fail("Choose two existing layers: the original and the simplified point set.");
    if (original->cm.vn == 0)
        return fail(QString("The original layer '%1' is empty.").arg(original->label()));
    if (simplified->cm.vn == 0)
        return fail(QString("The simplified layer '%1' is empty.").arg(simplified->label()));
    const QString noNormalsAdvice = "Compute them with Filters > Normals, Curvatures and Orientation > "
                                    "Compute normals for point sets.";
    if (CountNormals(simplified->cm) == 0)
        return fail(QString("The simplified layer '%1' has no normals (all are zero or invalid): it "
                            "defines no surface. %2")
                        .arg(simplified->label(), noNormalsAdvice));
    const int originalNormals = CountNormals(original->cm);
    if (originalNormals == 0)
        Log(GLLogStream::WARNING,
            "The original layer '%s' has no normals: only the distances are measured. %s",
            qUtf8Printable(original->label()), qUtf8Printable(noNormalsAdvice));

    vcg::gaussphere::metric::SurfelErrorParams params;
    params.neighborCount = par.getInt("NeighborCount");
    params.widthFactor = par.getFloat("WidthFactor");

    std::vector<vcg::Point3f> majorAxes, minorAxes;
    std::vector<int> representative;
    vcg::gaussphere::metric::SurfelErrorAttributes attributes;
    if (CopyPerVertexAttribute(simplified->cm, gs::kMajorAxisAttribute, majorAxes) &&
        CopyPerVertexAttribute(simplified->cm, gs::kMinorAxisAttribute, minorAxes)) {
        attributes.ellipseMajorAxes = &majorAxes;
        attributes.ellipseMinorAxes = &minorAxes;
    }
    std::vector<float> blendScale;
    if (CopyPerVertexAttribute(simplified->cm, gs::kBlendScaleAttribute, blendScale))
        attributes.blendScale = &blendScale;
    // On the same layer twice each point is its own surfel; its SurfelIndex names another layer.
    if (par.getBool("UseSurfelIndex") && original != simplified &&
        CopyPerVertexAttribute(original->cm, gs::kRepresentativeAttribute, representative)) {
        const int largest =
            representative.empty() ? -1 : *std::max_element(representative.begin(), representative.end());
        if (largest >= int(simplified->cm.vert.size()))
            return fail(
                QString("The SurfelIndex attribute of '%1' names surfel %2, but '%3' has %4 vertices: "
                        "it belongs to another simplified layer. Untick \"Own surfel from SurfelIndex\" "
                        "to compare against the nearest surfel.")
                    .arg(original->label())
                    .arg(largest)
                    .arg(simplified->label())
                    .arg(simplified->cm.vert.size()));
        attributes.representative = &representative;
    }

    QElapsedTimer timer;
    timer.start();
    std::vector<float> distance;
    vcg::gaussphere::metric::SurfelErrorStats stats;
    try {
        stats = vcg::gaussphere::metric::ComputeSurfelError(original->cm, simplified->cm, params, attributes, &distance, cb);
    } catch (const std::exception& e) {
        return fail(QString("Cannot measure: %1.").arg(e.what()));
    }
    const double seconds = timer.elapsed() / 1000.0;

    // Unmeasured points (non-finite position) get 0 so that colour ramps stay usable.
    original->updateDataMask(MeshModel::MM_VERTQUALITY);
    CMeshO& cm = original->cm;
    for (size_t i = 0; i < cm.vert.size(); ++i)
        cm.vert[i].Q() = std::isnan(distance[i]) ? 0.0f : distance[i];
    if (par.getBool("ColorizeByDistance")) {
        original->updateDataMask(MeshModel::MM_VERTCOLOR);
        // Reversed range: vcg's ramp is red at its first bound. The floor keeps a zero map valid.
        const float red = std::max(float(stats.distance.p999), std::numeric_limits<float>::min());
        vcg::tri::UpdateColor<CMeshO>::PerVertexQualityRamp(cm, red, 0.0f);
    }

    const vcg::gaussphere::metric::ErrorSummary &nd = stats.normalizedDistance, &d = stats.distance;
    Log("Surfel error of '%s' (%zu surfels) against '%s' (%zu points): D*rms %.3e D*max %.3e (p99.9 %.3e); "
        "absolute Drms %.3e Dmax %.3e (p99.9 %.3e), diagonal %.4g; %.2f s",
        qUtf8Printable(simplified->label()), stats.usableSurfelCount, qUtf8Printable(original->label()),
        d.count, nd.rms, nd.max, nd.p999, d.rms, d.max, d.p999, stats.diagonal, seconds);
    if (stats.normalToOwnSurfel.count > 0) {
        const vcg::gaussphere::metric::ErrorSummary &own = stats.normalToOwnSurfel, &blended = stats.normalToBlended;
        Log("Surfel error L2,1 |n-n'| over %zu points: own surfel (%s) rms %.4f max %.4f (p99.9 %.4f); "
            "blended normal rms %.4f max %.4f (p99.9 %.4f)",
            own.count, attributes.representative ? "SurfelIndex" : "nearest", own.rms, own.max, own.p999,
            blended.rms, blended.max, blended.p999);
    }

    const size_t unmeasured = stats.originalPointCount - d.count;
    if (unmeasured > 0)
        Log(GLLogStream::WARNING,
            "Surfel error: %zu original point(s) with an invalid position were not measured "
            "(quality 0)",
            unmeasured);
    if (originalNormals > 0 && stats.normalToOwnSurfel.count < d.count)
        Log(GLLogStream::WARNING,
            "Surfel error: %zu original point(s) without a valid normal count for the "
            "distances only",
            d.count - stats.normalToOwnSurfel.count);
    if (stats.usableSurfelCount < stats.surfelCount)
        Log(GLLogStream::WARNING,
            "Surfel error: %zu simplified point(s) without a valid position or normal "
            "were ignored",
            stats.surfelCount - stats.usableSurfelCount);
    if (attributes.representative && stats.ownSurfelFromNearestCount > 0)
        Log(GLLogStream::WARNING,
            "Surfel error: %zu point(s) have no surfel in SurfelIndex and were compared "
            "against the nearest surfel",
            stats.ownSurfelFromNearestCount);
    if (stats.unconvergedCount > 0)
        Log("Surfel error: %zu projection(s) did not settle within %d steps (their last position is used)",
            stats.unconvergedCount, params.maxIterations);
    return true;
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterSurfelErrorPlugin)
