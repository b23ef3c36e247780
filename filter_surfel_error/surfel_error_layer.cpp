#include "surfel_error_layer.h"

#include <QElapsedTimer>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <vcg_ext/surfel/surfel_attributes.h> // attribute names of docs/surfel_format.md
#include <vcg_ext/surfel_error/surfel_error.h>

namespace gs = vcg::gaussphere;
namespace metric = vcg::gaussphere::metric;

namespace surfel_error_filter {
namespace {

/// Copies a per-vertex attribute into a plain array; false when the layer has none of that
/// name and type.
template <class T>
bool CopyPerVertexAttribute(CMeshO &m, const char *name, std::vector<T> &values)
{
    auto handle = vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<T>(m, name);
    if (!vcg::tri::Allocator<CMeshO>::IsValidHandle(m, handle)) return false;
    values.resize(m.vert.size());
    for (size_t i = 0; i < m.vert.size(); ++i) values[i] = handle[i];
    return true;
}

bool HasSurfelIndex(const MeshModel &layer) { return vcg::tri::HasPerVertexAttribute(layer.cm, gs::kRepresentativeAttribute); }

/// Live vertices whose normal is non-zero and finite; 0 means the layer has no normals.
int CountNormals(const CMeshO &m)
{
    int count = 0;
    for (const CVertexO &v : m.vert) {
        const double length2 = vcg::Point3d::Construct(v.cN()).SquaredNorm();
        if (!v.IsD() && length2 > 0 && std::isfinite(length2)) ++count;
    }
    return count;
}

QString Format(const char *format, ...) __attribute__((format(printf, 1, 2)));
QString Format(const char *format, ...)
{
    va_list args, again;
    va_start(args, format);
    va_copy(again, args);
    std::vector<char> text(std::max(0, std::vsnprintf(nullptr, 0, format, args)) + 1);
    va_end(args);
    std::vsnprintf(text.data(), text.size(), format, again);
    va_end(again);
    return QString::fromUtf8(text.data());
}

/// The per-vertex attributes the metric reads, copied out of the layers; `attributes` points
/// into the copies.
struct AttributeCopies
{
    std::vector<vcg::Point3f> majorAxes, minorAxes;
    std::vector<float> blendScale;
    std::vector<int> representative;
    metric::SurfelErrorAttributes attributes;
};

/// The error when the layers cannot be measured; `originalNormals` counts the original's normals
/// (a layer without them is measured for the distances only, with a warning).
QString CheckLayers(MeshModel *original, MeshModel *simplified, int &originalNormals, std::vector<LogLine> &log)
{
    if (original == nullptr || simplified == nullptr)
        return "Choose two existing layers: the original and the simplified point set.";
    if (original->cm.vn == 0) return QString("The original layer '%1' is empty.").arg(original->label());
    if (simplified->cm.vn == 0) return QString("The simplified layer '%1' is empty.").arg(simplified->label());
    // The metric compares the layers' own coordinates; where each is drawn is its matrix times them.
    if (original->cm.Tr != simplified->cm.Tr)
        return QString("The layers '%1' and '%2' are placed by different transformation matrices, so their "
                       "coordinates do not correspond: apply the matrices first (Filters > Normals, Curvatures "
                       "and Orientation > Matrix: Freeze Current Matrix, on each layer).")
            .arg(original->label(), simplified->label());
    const QString noNormalsAdvice = "Compute them with Filters > Normals, Curvatures and Orientation > "
                                    "Compute normals for point sets.";
    if (CountNormals(simplified->cm) == 0)
        return QString("The simplified layer '%1' has no normals (all are zero or invalid): it "
                       "defines no surface. %2")
            .arg(simplified->label(), noNormalsAdvice);
    originalNormals = CountNormals(original->cm);
    if (originalNormals == 0)
        log.push_back({true, Format("The original layer '%s' has no normals: only the distances are measured. %s",
                                    qUtf8Printable(original->label()), qUtf8Printable(noNormalsAdvice))});
    return QString();
}

/// Copies the ellipse axes, blend scales and (with `useSurfelIndex`, on two layers) SurfelIndex;
/// the error when SurfelIndex names surfels the simplified layer lacks.
QString CopyAttributes(MeshModel &original, MeshModel &simplified, bool useSurfelIndex, AttributeCopies &copies)
{
    if (CopyPerVertexAttribute(simplified.cm, gs::kMajorAxisAttribute, copies.majorAxes) &&
        CopyPerVertexAttribute(simplified.cm, gs::kMinorAxisAttribute, copies.minorAxes)) {
        copies.attributes.ellipseMajorAxes = &copies.majorAxes;
        copies.attributes.ellipseMinorAxes = &copies.minorAxes;
    }
    if (CopyPerVertexAttribute(simplified.cm, gs::kBlendScaleAttribute, copies.blendScale))
        copies.attributes.blendScale = &copies.blendScale;
    // On the same layer twice each point is its own surfel; its SurfelIndex names another layer.
    std::vector<int> &representative = copies.representative;
    if (!useSurfelIndex || &original == &simplified ||
        !CopyPerVertexAttribute(original.cm, gs::kRepresentativeAttribute, representative))
        return QString();
    const int largest = representative.empty() ? -1 : *std::max_element(representative.begin(), representative.end());
    if (largest >= int(simplified.cm.vert.size()))
        return QString("The SurfelIndex attribute of '%1' names surfel %2, but '%3' has %4 vertices: "
                       "it belongs to another simplified layer. Untick \"Own surfel from SurfelIndex\" "
                       "to compare against the nearest surfel.")
            .arg(original.label())
            .arg(largest)
            .arg(simplified.label())
            .arg(simplified.cm.vert.size());
    copies.attributes.representative = &representative;
    return QString();
}

/// d(q) into the original's vertex quality, and with `colorize` a blue (0) to red (p99.9) map.
void StoreDistances(MeshModel &original, const std::vector<float> &distance, double p999, bool colorize)
{
    // Unmeasured points (non-finite position) get 0 so that colour ramps stay usable.
    original.updateDataMask(MeshModel::MM_VERTQUALITY);
    CMeshO &cm = original.cm;
    for (size_t i = 0; i < cm.vert.size(); ++i) cm.vert[i].Q() = std::isnan(distance[i]) ? 0.0f : distance[i];
    if (!colorize) return;
    original.updateDataMask(MeshModel::MM_VERTCOLOR);
    // Reversed range: vcg's ramp is red at its first bound. The floor keeps a zero map valid.
    const float red = std::max(float(p999), std::numeric_limits<float>::min());
    vcg::tri::UpdateColor<CMeshO>::PerVertexQualityRamp(cm, red, 0.0f);
}

/// The figures: distances, then the normal errors when the original has normals.
void LogFigures(const MeshModel &original, const MeshModel &simplified, const metric::SurfelErrorStats &stats,
                bool fromSurfelIndex, double seconds, std::vector<LogLine> &log)
{
    const metric::ErrorSummary &nd = stats.normalizedDistance, &d = stats.distance;
    log.push_back({false, Format("Surfel error of '%s' (%zu surfels) against '%s' (%zu points): D*rms %.3e D*max %.3e "
                                 "(p99.9 %.3e); absolute Drms %.3e Dmax %.3e (p99.9 %.3e), diagonal %.4g; %.2f s",
                                 qUtf8Printable(simplified.label()), stats.usableSurfelCount,
                                 qUtf8Printable(original.label()), d.count, nd.rms, nd.max, nd.p999, d.rms, d.max,
                                 d.p999, stats.diagonal, seconds)});
    if (stats.normalToOwnSurfel.count == 0) return;
    const metric::ErrorSummary &own = stats.normalToOwnSurfel, &blended = stats.normalToBlended;
    log.push_back({false, Format("Surfel error L2,1 |n-n'| over %zu points: own surfel (%s) rms %.4f max %.4f (p99.9 "
                                 "%.4f); blended normal rms %.4f max %.4f (p99.9 %.4f)",
                                 own.count, fromSurfelIndex ? "SurfelIndex" : "nearest", own.rms, own.max, own.p999,
                                 blended.rms, blended.max, blended.p999)});
}

/// What was not measured, or measured in part, and why.
void LogSkipped(const metric::SurfelErrorStats &stats, int originalNormals, bool fromSurfelIndex, int maxIterations,
                std::vector<LogLine> &log)
{
    const size_t measured = stats.distance.count;
    if (stats.originalPointCount > measured)
        log.push_back({true, Format("Surfel error: %zu original point(s) with an invalid position were not measured "
                                    "(quality 0)",
                                    stats.originalPointCount - measured)});
    if (originalNormals > 0 && stats.normalToOwnSurfel.count < measured)
        log.push_back({true, Format("Surfel error: %zu original point(s) without a valid normal count for the "
                                    "distances only",
                                    measured - stats.normalToOwnSurfel.count)});
    if (stats.usableSurfelCount < stats.surfelCount)
        log.push_back({true, Format("Surfel error: %zu simplified point(s) without a valid position or normal "
                                    "were ignored",
                                    stats.surfelCount - stats.usableSurfelCount)});
    if (fromSurfelIndex && stats.ownSurfelFromNearestCount > 0)
        log.push_back({true, Format("Surfel error: %zu point(s) have no surfel in SurfelIndex and were compared "
                                    "against the nearest surfel",
                                    stats.ownSurfelFromNearestCount)});
    if (stats.unconvergedCount > 0)
        log.push_back({false, Format("Surfel error: %zu projection(s) did not settle within %d steps (their last "
                                     "position is used)",
                                     stats.unconvergedCount, maxIterations)});
}

} // namespace

QString PluginName() { return "FilterSurfelError"; }

QString FilterName() { return "Surfel Approximation Error"; }

QString FilterInfo()
{
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
           "distances only. They are compared in their own coordinates, so they must share their "
           "transformation matrix (the resampling's output takes its input's).<br>"
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
}

const LayerParameter kOriginalLayer = {
    "OriginalMesh", "Original point set",
    "The original oriented point set S: every one of its points is measured. Its vertex quality "
    "receives the distance to the simplified surface."};
const LayerParameter kSimplifiedLayer = {
    "SimplifiedMesh", "Simplified point set",
    "The simplified point set S' (surfels, or plain oriented points) that defines the surface the "
    "original points are projected onto. Choose the original layer again to measure the floor of "
    "the metric."};

LayerChoice DefaultLayers(const MeshDocument &md)
{
    // Right after a resampling the current layer is its output and the input carries SurfelIndex.
    const std::vector<const MeshModel *> layers = meshlab_glue::Layers(md);
    const MeshModel *current = md.mm(), *original = current;
    for (const MeshModel *layer : layers)
        if (HasSurfelIndex(*layer)) {
            original = layer;
            break;
        }
    const MeshModel *simplified = original;
    if (current != original)
        simplified = current;
    else
        for (const MeshModel *layer : layers)
            if (layer != original) {
                simplified = layer;
                break;
            }
    LayerChoice choice;
    if (original != nullptr) choice.original = int(original->id());
    if (simplified != nullptr) choice.simplified = int(simplified->id());
    return choice;
}

void AddOptionParameters(RichParameterList &par)
{
    const metric::SurfelErrorParams defaults;
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

MeasureOutcome Measure(MeshModel *original, MeshModel *simplified, const RichParameterList &par,
                       vcg::CallBackPos *cb)
{
    MeasureOutcome outcome;
    int originalNormals = 0;
    outcome.error = CheckLayers(original, simplified, originalNormals, outcome.log);
    if (!outcome.error.isEmpty()) return outcome;
    metric::SurfelErrorParams params;
    params.neighborCount = par.getInt("NeighborCount");
    params.widthFactor = par.getFloat("WidthFactor");
    AttributeCopies copies;
    outcome.error = CopyAttributes(*original, *simplified, par.getBool("UseSurfelIndex"), copies);
    if (!outcome.error.isEmpty()) return outcome;

    QElapsedTimer timer;
    timer.start();
    std::vector<float> distance;
    metric::SurfelErrorStats stats;
    try {
        stats = metric::ComputeSurfelError(original->cm, simplified->cm, params, copies.attributes, &distance, cb);
    } catch (const std::exception &e) {
        outcome.error = QString("Cannot measure: %1.").arg(e.what());
        return outcome;
    }
    const double seconds = timer.elapsed() / 1000.0;
    StoreDistances(*original, distance, stats.distance.p999, par.getBool("ColorizeByDistance"));
    const bool fromSurfelIndex = copies.attributes.representative != nullptr;
    LogFigures(*original, *simplified, stats, fromSurfelIndex, seconds, outcome.log);
    LogSkipped(stats, originalNormals, fromSurfelIndex, params.maxIterations, outcome.log);
    return outcome;
}

} // namespace surfel_error_filter
