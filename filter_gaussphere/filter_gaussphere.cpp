#include "filter_gaussphere.h"

#include <cmath>

#include <vcg_ext/gaussphere/resampling.h>
#include <vcg_ext/gaussphere/surfel_mesh.h>

namespace gs = vcg::gaussphere;

FilterGaussSpherePlugin::FilterGaussSpherePlugin()
{
    typeList << FP_GAUSSPHERE_RESAMPLING;
    for (FilterIDType t : types())
        actionList << new QAction(filterName(t), this);
}

QString FilterGaussSpherePlugin::pluginName() const { return "FilterGaussSphere"; }

QString FilterGaussSpherePlugin::filterName(FilterIDType filter) const
{
    switch (filter) {
    case FP_GAUSSPHERE_RESAMPLING: return "Gaussian Sphere Feature-Sensitive Resampling";
    default: return QString();
    }
}

QString FilterGaussSpherePlugin::filterInfo(FilterIDType filter) const
{
    switch (filter) {
    case FP_GAUSSPHERE_RESAMPLING:
        return "Feature-sensitive resampling of an oriented point set into elliptical surfels.<br>"
               "Points are clustered by where their normals fall on a subdivided Gaussian sphere: "
               "labels spread between neighbours whose normals share a Gaussian triangle, one-point "
               "clusters rejoin their most similar neighbour, and elongated clusters are split until "
               "they are disc-like. Each cluster becomes one surfel, so the output is dense where "
               "the normals vary (edges, ridges, fine detail) and sparse on flat parts.<br>"
               "The result is a new layer <i>&lt;name&gt; resampled</i> with unit normals, per-vertex "
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
    default: return QString();
    }
}

MeshFilterInterface::FilterClass FilterGaussSpherePlugin::getClass(QAction *)
{
    return FilterClass(MeshFilterInterface::PointSet | MeshFilterInterface::Remeshing);
}

MeshFilterInterface::FILTER_ARITY FilterGaussSpherePlugin::filterArity(QAction *) const { return SINGLE_MESH; }

// Normals are always allocated in CMeshO; whether they mean anything is checked at run time.
int FilterGaussSpherePlugin::getPreConditions(QAction *) const { return MeshModel::MM_NONE; }

int FilterGaussSpherePlugin::postCondition(QAction *) const { return MeshModel::MM_VERTCOLOR; }

void FilterGaussSpherePlugin::initParameterSet(QAction *, MeshModel &m, RichParameterList &par)
{
    const gs::ResamplingParams defaults;
    const float diag = m.cm.bbox.Diag();
    par.addParam(RichInt("SubdivisionLevel", defaults.subdivisionLevel, "Gaussian sphere level",
        "Level n of the Gaussian sphere subdivision (2-256): each face of an icosahedron is cut into "
        "(n-1)^2 triangles. Higher levels separate finer normal variations, giving more surfels and "
        "lower error; the paper uses 8, 16 and 24."));
    par.addParam(RichInt("NeighborCount", defaults.neighborCount, "Nearest neighbours",
        "Number k of nearest neighbours examined around each point (1-255). Only those inside the "
        "cone of normals of the Gaussian sphere level are kept as adaptive neighbours."));
    par.addParam(RichInt("PropagationDepth", defaults.propagationDepth, "Propagation depth",
        "How many neighbour hops a cluster label may travel from its seed point (0 = no limit). "
        "Small values make many small clusters; large ones let clusters grow across flat regions."));
    par.addParam(RichFloat("NormalizationThreshold", defaults.normalizationThreshold, "Normalization threshold",
        "A cluster whose positions have a covariance with lambda1/lambda2 above this value is split "
        "in two through its centroid, perpendicular to its major axis (must be greater than 1)."));
    par.addParam(RichInt("MinSplitSize", defaults.minSplitSize, "Minimum cluster size to split",
        "Clusters with fewer points are never split: their shape estimate is dominated by noise."));
    par.addParam(RichInt("MaxClusterSize", defaults.maxClusterSize, "Maximum cluster size",
        "Clusters with more points are split whatever their shape (0 = no limit), so that flat regions "
        "are covered by surfels of bounded size rather than a few huge ones."));
    par.addParam(RichFloat("CreaseAngle", defaults.creaseAngle, "Crease angle (degrees)",
        "A point lies on a crease when one of its nearest neighbours has a normal turned by more than "
        "this angle (and less than 120 degrees, beyond which it is the other side of a thin part). "
        "Clusters touching a crease are kept small, so that surfels do not round sharp edges off "
        "(0 = off, below 120)."));
    par.addParam(RichInt("CreaseClusterSize", defaults.creaseClusterSize, "Maximum cluster size at creases",
        "Clusters touching a crease are split above this many points (0 = no limit); from 4 points on "
        "they are also split when elongated along the edge."));
    par.addParam(RichFloat("CreaseBlendScale", defaults.creaseBlendScale, "Blend width at creases",
        "Factor in (0, 1] on the width of the blend weight of the surfels around a crease (clusters of more "
        "than one point holding a crease point or one of its neighbours; per-vertex attribute SurfelBlendScale): "
        "the surface the surfels blend into (the moving least squares surface the Surfel Approximation Error "
        "filter measures on) then follows each face closer to the edge instead of rounding it off. "
        "The ellipses keep their size, and FitOffsets leaves these surfels in place. 1 = off; needs a Crease "
        "angle. With a Maximum error the bound is checked on the narrowed blend, "
        "which meets it with fewer surfels on CAD parts."));
    par.addParam(RichAbsPerc("WeightWidth", 0.01f * diag, 0.0f, diag, "Normal weight width (h)",
        "Width h of the Gaussian weight exp(-r^2/h^2) used to blend the normals of a cluster into the "
        "surfel normal, r being the distance to the cluster centroid. 0 means 1% of the bounding box "
        "diagonal, the default."));
    par.addParam(RichInt("MaxIterations", defaults.maxIterations, "Maximum iterations",
        "Upper bound on the rounds of cluster normalization and singleton rejoining; rounds stop "
        "earlier once the number of clusters changes by less than 1% of the number of points."));
    par.addParam(RichInt("TargetCount", 0, "Target surfel count",
        "Exact number of surfels wanted (0 = off): the filter picks the finest Gaussian sphere level "
        "that gives no more, then splits the clusters with the largest normal error until the count "
        "is reached (or, from a level giving at most 15% more, or below what level 2 gives, merges "
        "the most similar neighbouring clusters). "
        "Overrides the Gaussian sphere level. Takes precedence over Target percentage."));
    par.addParam(RichFloat("TargetPercentage", 0.0f, "Target percentage",
        "Number of surfels wanted as a percentage of the input points (0 = off), e.g. 10 for one "
        "surfel per ten points. Used when Target surfel count is 0."));
    par.addParam(RichInt("MaxErrorExchanges", defaults.maxErrorExchanges, "Exchanges for the largest error",
        "With a target count or percentage: at most this many exchanges of clusters that lower the largest "
        "distance from an input point to the surface the surfels blend into, keeping the count (0 = off). "
        "Each exchange splits a cluster at the worst point and merges the most similar pair of neighbouring "
        "clusters elsewhere, and is kept only if the largest distance went down; the log gives it before "
        "and after. Last, the surfels left unfitted at creases are fitted to the blend where that lowers the "
        "squared distances without raising the largest or the 99.9th percentiles. On the benchmark's 16 models "
        "at 5 to 30% the exchanges lowered the largest distance by 30% (median; 0 to 62%), and the run took "
        "2.3 times as long (median; 1.2 to 5.2 times); the crease fit lowered the RMS distance by 13% "
        "(geometric mean) and about doubles the time again on large scans. "
        "Not used with a Maximum error, whose bound sets the count."));
    par.addParam(RichFloat("MaxError", 0.0f, "Maximum error (fraction of diagonal)",
        "Optional bound on the distance from every input point to the surface the surfels define, as a "
        "fraction of the bounding box diagonal, e.g. 0.002 (0 = off). Clusters are split until every point "
        "lies within it of its own surfel's plane, then of the blended surface of all surfels (as the Surfel "
        "Approximation Error filter measures it). Near sharp creases that blend rounds the edge even when "
        "every surfel is one point: there the blend weight of one-point surfels is narrowed (down to 1/8, "
        "per-vertex attribute SurfelBlendScale) until the blend follows them; their ellipses keep their size, "
        "so splat renderings keep covering the surface. Points still beyond the bound are counted in the log. "
        "With a target count, the bound wins when both cannot hold."));
    par.addParam(RichBool("FitOffsets", defaults.fitOffsets, "Fit surfels to the blended surface",
        "Move each surfel along its normal so that the surface the surfels blend into (the moving least "
        "squares surface the Surfel Approximation Error filter measures on) passes through the input points on average, "
        "instead of leaving the surfel at its cluster's centroid, which lies inside curved surfaces. Lowers "
        "the distance error of smooth scans by a quarter to a third at little cost; clusters at sharp creases "
        "keep their place, and so do the surfels whose blend is narrowed around them. Each move is kept in the per-vertex attribute <i>SurfelFitOffset</i> (and in .surfel "
        "files), from which the Ellipse Splatting render mode draws each splat at its unfitted position, on the "
        "sampled surface: splats blend shading, not positions, and fitted ones would swell the silhouettes. "
        "With a Maximum error the surfels are fitted in every round of its check, so the bound holds for them."));
    par.addParam(RichBool("ColorizeClusters", false, "Colour input by cluster",
        "Give every cluster a random colour on the input layer's vertices, to inspect the clustering."));
}

bool FilterGaussSpherePlugin::applyFilter(QAction *filter, MeshDocument &md, const RichParameterList &par,
                                          vcg::CallBackPos *cb)
{
    switch (ID(filter)) {
    case FP_GAUSSPHERE_RESAMPLING: return resample(md, par, cb);
    default: return false;
    }
}

// meshlabserver does not print errorMsg(), only the log: say it in both.
bool FilterGaussSpherePlugin::fail(const QString &message)
{
    errorMessage = message;
    Log(GLLogStream::WARNING, "Gaussian sphere resampling failed: %s", qUtf8Printable(message));
    return false;
}

bool FilterGaussSpherePlugin::resample(MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb)
{
    MeshModel *input = md.mm();
    if (input == nullptr || input->cm.vn == 0) {
        return fail("The current layer is empty: there are no points to resample.");
    }
    CMeshO &in = input->cm;
    int withNormal = 0;
    for (const CVertexO &v : in.vert)
        if (!v.IsD() && v.cN().SquaredNorm() > 0 && std::isfinite(v.cN().SquaredNorm())) ++withNormal;
    if (withNormal == 0) {
        return fail("The layer has no normals (all are zero or invalid). Compute them first with "
                       "Filters > Normals, Curvatures and Orientation > Compute normals for point sets.");
    }

    gs::ResamplingParams param;
    param.subdivisionLevel = par.getInt("SubdivisionLevel");
    param.neighborCount = par.getInt("NeighborCount");
    param.propagationDepth = par.getInt("PropagationDepth");
    param.normalizationThreshold = par.getFloat("NormalizationThreshold");
    param.minSplitSize = par.getInt("MinSplitSize");
    param.maxClusterSize = par.getInt("MaxClusterSize");
    param.creaseAngle = par.getFloat("CreaseAngle");
    param.creaseClusterSize = par.getInt("CreaseClusterSize");
    param.creaseBlendScale = par.getFloat("CreaseBlendScale");
    const float width = par.getAbsPerc("WeightWidth");
    param.weightWidth = width > 0 ? width : -1.0;
    param.maxIterations = par.getInt("MaxIterations");
    const int targetCount = par.getInt("TargetCount");
    const float targetPercentage = par.getFloat("TargetPercentage");
    if (targetCount < 0 || !(targetPercentage >= 0 && targetPercentage <= 100))
        return fail("TargetCount must not be negative and TargetPercentage must be between 0 and 100.");
    param.targetCount = targetCount > 0 ? targetCount
                      : targetPercentage > 0 ? std::max(1, int(std::lround(targetPercentage / 100.0 * withNormal)))
                                             : 0;
    param.maxErrorFraction = par.getFloat("MaxError");
    param.fitOffsets = par.getBool("FitOffsets");
    param.maxErrorExchanges = par.getInt("MaxErrorExchanges");
    const std::string invalid = param.Validate();
    if (!invalid.empty()) {
        return fail(QString::fromStdString(invalid) + ".");
    }

    gs::ResamplingResult result;
    try {
        result = gs::ResamplePointSet(in, param, cb);
    } catch (const gs::ResamplingCancelled &) {
        return fail("Resampling was cancelled.");
    } catch (const std::exception &e) {
        return fail(QString("Cannot resample: %1.").arg(e.what()));
    }

    auto representative = vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<int>(in, gs::kRepresentativeAttribute);
    for (size_t i = 0; i < in.vert.size(); ++i) representative[i] = result.representative[i];
    if (par.getBool("ColorizeClusters")) {
        input->updateDataMask(MeshModel::MM_VERTCOLOR);
        const int clusters = std::max(1, int(result.surfels.size()));
        for (size_t i = 0; i < in.vert.size(); ++i) {
            const int c = result.representative[i];
            // Scatter spreads neighbouring indices over distant hues.
            in.vert[i].C() = c < 0 ? vcg::Color4b::Gray : vcg::Color4b::Scatter(std::min(clusters, 4096), c % 4096);
        }
    }

    MeshModel *output = md.addNewMesh("", input->label() + " resampled", true);
    output->updateDataMask(MeshModel::MM_VERTRADIUS | MeshModel::MM_VERTQUALITY);
    gs::WriteSurfels(result.surfels, output->cm);
    if (input->hasDataMask(MeshModel::MM_VERTCOLOR)) {
        // Each surfel takes the mean colour of the points it represents (the cluster
        // colours when ColorizeClusters painted them).
        output->updateDataMask(MeshModel::MM_VERTCOLOR);
        std::vector<vcg::Point4d> sum(result.surfels.size(), vcg::Point4d(0, 0, 0, 0));
        std::vector<int> members(result.surfels.size(), 0);
        for (size_t i = 0; i < in.vert.size(); ++i) {
            const int c = result.representative[i];
            if (c < 0) continue;
            const vcg::Color4b &col = in.vert[i].cC();
            sum[c] += vcg::Point4d(col[0], col[1], col[2], col[3]);
            ++members[c];
        }
        for (size_t c = 0; c < sum.size(); ++c) {
            const vcg::Point4d mean = sum[c] / std::max(1, members[c]);
            output->cm.vert[c].C() = vcg::Color4b((unsigned char)std::lround(mean[0]), (unsigned char)std::lround(mean[1]),
                                                  (unsigned char)std::lround(mean[2]), (unsigned char)std::lround(mean[3]));
        }
    }

    const gs::ResamplingStats &s = result.stats;
    Log("Gaussian sphere resampling: %d points -> %d surfels (%.2f%%), level %d, %d iteration(s), "
        "%.1f adaptive neighbours per point, L2,1 RMS %.4f; time %.3f s on %d thread(s) (neighbours %.3f, propagation %.3f, "
        "normalization %.3f, refinement %.3f, surfels %.3f, exchanges %.3f)",
        s.inputCount - s.skippedCount, s.outputCount, 100.0 * s.outputCount / std::max(1, s.inputCount - s.skippedCount),
        s.levelUsed, s.iterations, s.meanAdaptiveNeighbors, s.normalErrorRms, s.TotalSeconds(), s.threadsUsed, s.secondsNeighbors,
        s.secondsPropagation, s.secondsNormalization, s.secondsRefinement, s.secondsSurfels, s.secondsExchanges);
    if (s.surfelsNarrowedAtCreases > 0)
        Log("Gaussian sphere resampling: %d surfel(s) around creases blend %.2f times as wide", s.surfelsNarrowedAtCreases,
            param.creaseBlendScale);
    if (s.surfelsFitted > 0)
        Log("Gaussian sphere resampling: %d surfel(s) fitted to the blended surface (longest move %g = %.5f x diagonal)",
            s.surfelsFitted, s.largestFitMove * s.diagonal, s.largestFitMove);
    if (param.targetCount > 0 || param.maxErrorFraction > 0)
        Log("Gaussian sphere resampling control: level %d chosen after %d tried, %d split(s) and %d merge(s) "
            "for the target count, %d + %d split(s) for the error bound (own planes + blended surface), "
            "%d halving(s) of one-point surfels' blend scales",
            s.levelUsed, s.levelsTried, s.splitsForTarget, s.mergesForTarget, s.splitsForErrorBound,
            s.splitsForSurfaceBound, s.narrowingsForSurfaceBound);
    if (s.exchangeTrials > 0)
        Log("Gaussian sphere resampling: %d exchange(s) of clusters kept of %d tried, largest distance to the "
            "blended surface %.3g -> %.3g x diagonal, then %d surfel(s) at creases fitted to the blend (%.3f s)",
            s.exchangesForMaxError, s.exchangeTrials, s.exchangeMaxBefore, s.exchangeMaxAfter, s.creaseFitsForMaxError,
            s.secondsExchanges);
    if (param.maxErrorFraction > 0) {
        const double diagonal = s.diagonal;
        if (s.pointsAboveErrorBound == 0)
            Log("Gaussian sphere resampling error bound met: every point within %g of the blended surface "
                "(largest distance %g = %.5f x diagonal, %d projection round(s))",
                param.maxErrorFraction * diagonal, s.surfaceErrorMax * diagonal, s.surfaceErrorMax, s.surfaceBoundRounds);
        else
            Log(GLLogStream::WARNING,
                "Gaussian sphere resampling error bound: %d point(s) remain beyond %g of the blended surface "
                "(largest %g = %.5f x diagonal): %s",
                s.pointsAboveErrorBound, param.maxErrorFraction * diagonal, s.surfaceErrorMax * diagonal,
                s.surfaceErrorMax,
                s.SurfaceBoundCapped()
                    ? "the refinement stopped at its cap of projection rounds"
                    : "the surfels around them are split and narrowed as far as they go, and the blend cannot "
                      "follow sharp creases or thin parts closer at this sampling");
    }
    if (param.targetCount > 0 && s.outputCount != param.targetCount)
        Log(GLLogStream::WARNING, "Gaussian sphere resampling: %d surfels instead of the %d requested (%s)",
            s.outputCount, param.targetCount,
            s.outputCount > param.targetCount
                ? "the error bound needs more"
                : "no cluster left to split");
    if (s.skippedCount > 0)
        Log(GLLogStream::WARNING, "Gaussian sphere resampling skipped %d point(s) with a zero or invalid normal",
            s.skippedCount);
    return true;
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterGaussSpherePlugin)
