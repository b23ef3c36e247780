// The resampler's parameters: the struct ResamplePointSet reads, and the one table that
// describes each of them (name, option, range, default, help). The MeshLab dialog, gsresample's
// options and --help, the README's parameter table and the shipped .mlx scripts are all made
// from the table (tools/gsparams prints the README table and the scripts; tests compare).
#ifndef VCG_EXT_GAUSSPHERE_RESAMPLING_PARAMS_H
#define VCG_EXT_GAUSSPHERE_RESAMPLING_PARAMS_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <vcg_ext/gaussphere/size_control/crease_fit_limits.h>
#include <vcg_ext/surfel/surfel.h>

namespace vcg {
namespace gaussphere {

/// What sets the number of surfels: one of three, chosen by ResamplingParams::SizeMode().
enum class SizeControl
{
    Level,       ///< the Gaussian sphere level alone (the paper)
    TargetCount, ///< an exact count: the level found by search, then split or merged to it
    ErrorBound   ///< as many surfels as the bound needs
};

/// Tuning of the stages where the paper is silent: each value is the one docs/algorithm.md
/// justifies; tests vary them to check the stages they steer. Only maxClusterSize is a parameter
/// (expert).
struct ResamplingTuning
{
    int minSplitSize = 8;          ///< clusters smaller than this are never split: their covariance is noise
    int maxClusterSize = 32;       ///< larger clusters are split whatever their shape, so that flat faces do not
                                   ///< become a few huge surfels whose blend bleeds over creases (0 = off)
    int creaseClusterSize = 5;     ///< maxClusterSize of clusters at a crease: wide surfels round edges off (0 = off)
    int creaseMinSplitSize = 4;    ///< minSplitSize of clusters at a crease
    float creaseBlendScale = 0.65f; ///< blend width of the surfels around creases, in (0, 1] (crease_blend.h)
    int maxIterations = 6;         ///< rounds of normalization and rejoining at most (they stop when nothing splits)
    double coverageMargin = 0.75;  ///< ellipse growth, in local sample spacings, so that neighbours overlap
    double mergeWithin = 1.15;     ///< TargetCount: merge down from a level giving at most this x the target
    std::uint32_t seedSalt = 0;    ///< mixed into the seed order's hash (seed_order.h): each value is another,
                                   ///< equally valid draw of where clusters start (bench/seed_spread.py)

    /// Empty when valid, else a message naming the field.
    std::string Validate() const
    {
        if (minSplitSize < 0 || maxClusterSize < 0) return "MinSplitSize and MaxClusterSize must not be negative";
        if (creaseClusterSize < 0 || creaseClusterSize == 1) return "CreaseClusterSize must be 0 (off) or at least 2";
        if (creaseMinSplitSize < 0) return "CreaseMinSplitSize must not be negative";
        if (!(creaseBlendScale > 0 && creaseBlendScale <= 1)) return "CreaseBlendScale must be above 0 and at most 1";
        if (maxIterations < 0) return "MaxIterations must not be negative";
        if (!(coverageMargin >= 0)) return "CoverageMargin must not be negative";
        if (!(mergeWithin >= 1)) return "MergeWithin must be at least 1";
        return std::string();
    }
};

struct ResamplingParams
{
    // Size control: the error bound, else the target count, else the target percentage, else the level.
    int subdivisionLevel = 8;      ///< n of the Gaussian sphere; with a target, the level its search starts from
    int targetCount = 0;           ///< exact number of surfels (0 = off)
    double targetPercentage = 0;   ///< exact number of surfels as a percentage of the usable points, copies counted once (0 = off)
    double maxErrorFraction = 0;   ///< bound on each point's distance to the surfels' blended surface, as a
                                   ///< fraction of the bounding-box diagonal (0 = off)
    // Shape of the result.
    int neighborCount = 16;        ///< k of the k-NN search (the paper's k)
    double creaseAngle = 45;       ///< degrees: a neighbour's normal turned by more marks a crease (0 = off)
    bool fitOffsets = true;        ///< surfels moved along their normals onto the blended surface (surfel_offset.h)
    // The paper's other knobs, and the exchanges: for reproducing the paper and for experts.
    int propagationDepth = 6;      ///< hops a label may travel from its seed (0 = unlimited)
    double normalizationThreshold = 6.0; ///< clusters with lambda1/lambda2 above it are split
    double weightWidth = 0;        ///< h of the surfel normal weights, in model units (0 = 1 % of the diagonal)
    int maxErrorExchanges = 16;    ///< TargetCount: exchanges of clusters that lower the largest error (0 = off)
    bool spreadEvenly = false;     ///< for surface reconstruction: the size control's count of surfels grown from
                                   ///< single points by merging, spread evenly (ResampleEvenly); not with maxErrorFraction
    /// TargetCount: search the level (false: split or merge the clusters of subdivisionLevel). Not a
    /// user's parameter: the tiles of a tiled run (tools/gstile) take the level the whole input gives.
    bool searchLevel = true;
    /// TargetCount without exchanges: keep the splits or merges that reached the count in
    /// ResamplingResult::targetRecord (the probes of a tiled run read them). Not a user's parameter.
    bool recordCountSteps = false;
    /// TargetCount with exchanges: the rounds of exchanges, when fewer than maxErrorExchanges (-1:
    /// maxErrorExchanges; 0: none, the crease fit after them only). A tile of a tiled run takes its
    /// part of the whole run's rounds (tools/gstile). Not a user's parameter.
    int exchangeRounds = -1;
    /// TargetCount with exchanges: only the mesh's first this many vertices count for the largest
    /// distance the exchanges lower (0: every vertex). A tile of a tiled run gives its core points,
    /// which come first: its halo's points are other tiles' to lower. Not a user's parameter.
    int countedVertices = 0;
    /// TargetCount with exchanges: the percentiles the crease fit after them is judged against, the
    /// distance in model units (not given: the run's own). A tile of a tiled run takes the whole
    /// scan's (tools/gstile). Not a user's parameter.
    CreaseFitLimits creaseFitLimits;
    /// TargetCount with exchanges: on entry to the crease fit, report this many of the highest
    /// figures of the points that count (ResamplingResult::creaseFitEntry; 0: none), from which a
    /// tiled run gathers the whole scan's limits. Not a user's parameter.
    int reportHighestAtCreaseFit = 0;
    /// TargetCount with exchanges and countedVertices: surfels kept by other runs around this one,
    /// in model units (a tile's neighbours' beyond its faces). After the crease fit, seam rounds of
    /// exchanges measure every point on them in place of the clusters this run does not keep (those
    /// whose anchor, the member of smallest anchorKeys entry, is not counted) and lower the largest
    /// distance of any point so measured, counted or not, down to seamTarget, passing over a point
    /// no exchange of this run lowers. Not a user's parameter.
    std::vector<Surfel> surroundingSurfels;
    /// ... the largest distance the seam rounds lower to, in model units (0: the one this run
    /// reached without them). A tile takes the largest the other tiles reached. Not a user's parameter.
    double seamTarget = 0;
    /// ... per vertex (empty: the vertex index). A tile of a tiled run gives its points' input
    /// indices, as its ownership rule reads them (tools/gstile). Not a user's parameter.
    std::vector<std::uint64_t> anchorKeys;

    ResamplingTuning tuning;

    SizeControl SizeMode() const
    {
        if (maxErrorFraction > 0) return SizeControl::ErrorBound;
        if (targetCount > 0 || targetPercentage > 0) return SizeControl::TargetCount;
        return SizeControl::Level;
    }
    /// The exact count wanted from `usablePoints` points (TargetCount mode): targetCount, else the
    /// percentage rounded, at least 1.
    int TargetFor(int usablePoints) const
    {
        if (targetCount > 0) return targetCount;
        return std::max(1, int(std::lround(targetPercentage / 100.0 * usablePoints)));
    }
    /// Empty when valid, else a message naming the offending parameter.
    std::string Validate() const;
};

enum class ParameterKind { Int, Float, Bool };

/// Who sees a parameter: everyone (the MeshLab dialog, gsresample, the README's main table), or
/// experts (gsresample and the README's expert table; the dialog uses the default).
enum class ParameterAudience { Everyone, Expert };

struct ParameterSpec
{
    const char *name;     ///< MeshLab's and the .mlx scripts' name
    const char *option;   ///< gsresample's option
    const char *label;    ///< the dialog's label
    ParameterKind kind;
    double defaultValue;
    double min, max;      ///< valid values: min <= v <= max, or min < v (< max) where open; max may be infinite
    bool minOpen, maxOpen;
    ParameterAudience audience;
    const char *help;     ///< one sentence: the dialog's tooltip, --help, the README
    double (*get)(const ResamplingParams &); ///< null for options of the host (ColorizeClusters)
    void (*set)(ResamplingParams &, double);

    bool Accepts(double v) const
    {
        if (!std::isfinite(v)) return false;
        if (kind == ParameterKind::Int && v != std::floor(v)) return false;
        return (minOpen ? v > min : v >= min) && (maxOpen ? v < max : v <= max);
    }
    /// "between 2 and 256", "above 1", ...: the valid values in words.
    std::string RangeText() const
    {
        const auto number = [](double v) {
            char text[32];
            std::snprintf(text, sizeof text, "%g", v);
            return std::string(text);
        };
        const bool unbounded = std::isinf(max);
        if (kind == ParameterKind::Bool) return "0 or 1";
        if (unbounded) return (minOpen ? "above " : "at least ") + number(min);
        if (!minOpen && !maxOpen) return "between " + number(min) + " and " + number(max);
        return (minOpen ? "above " : "at least ") + number(min) + (maxOpen ? " and below " : " and at most ") + number(max);
    }
};

/// The parameters, in dialog order.
inline const std::vector<ParameterSpec> &ParameterTable()
{
    using P = ResamplingParams;
    const double unbounded = std::numeric_limits<double>::infinity();
    static const std::vector<ParameterSpec> table = {
        {"SubdivisionLevel", "--level", "Gaussian sphere level", ParameterKind::Int, 8, 2, 256, false, false,
         ParameterAudience::Everyone,
         "Level n of the Gaussian sphere: each face of an icosahedron is cut into (n-1)^2 triangles; higher levels "
         "separate finer normal variations and give more surfels (the paper uses 8, 16 and 24).",
         [](const P &p) { return double(p.subdivisionLevel); }, [](P &p, double v) { p.subdivisionLevel = int(v); }},
        {"TargetCount", "--target", "Target surfel count", ParameterKind::Int, 0, 0, unbounded, false, false,
         ParameterAudience::Everyone,
         "Exact number of surfels (0 = off): the level is searched for, then clusters are split or merged to the "
         "count; overrides the level and the percentage.",
         [](const P &p) { return double(p.targetCount); }, [](P &p, double v) { p.targetCount = int(v); }},
        {"TargetPercentage", "--percentage", "Target percentage", ParameterKind::Float, 0, 0, 100, false, false,
         ParameterAudience::Everyone,
         "Exact number of surfels as a percentage of the usable input points, those with a finite position and a "
         "finite, non-zero normal, copies of a point counted once (0 = off), e.g. 10 for one surfel per ten "
         "points; overrides the level.",
         [](const P &p) { return p.targetPercentage; }, [](P &p, double v) { p.targetPercentage = v; }},
        {"MaxError", "--max-error", "Maximum error (fraction of diagonal)", ParameterKind::Float, 0, 0, 1, false, true,
         ParameterAudience::Everyone,
         "Bound on the distance from every input point to the surface the surfels blend into, as a fraction of the "
         "bounding-box diagonal, e.g. 0.002 (0 = off); clusters are split until it holds, and it overrides the other "
         "size controls.",
         [](const P &p) { return p.maxErrorFraction; }, [](P &p, double v) { p.maxErrorFraction = v; }},
        {"NeighborCount", "--k", "Nearest neighbours", ParameterKind::Int, 16, 1, 255, false, false,
         ParameterAudience::Everyone,
         "Number k of nearest neighbours examined around each point; those inside the cone of normals of the level "
         "are its adaptive neighbours.",
         [](const P &p) { return double(p.neighborCount); }, [](P &p, double v) { p.neighborCount = int(v); }},
        {"CreaseAngle", "--crease-angle", "Crease angle (degrees)", ParameterKind::Float, 45, 0, 120, false, true,
         ParameterAudience::Everyone,
         "A point whose neighbour's normal is turned by more than this angle lies on a crease, where clusters are "
         "kept small so that surfels do not round sharp edges off; the rim of an open surface gets the same limits "
         "(0 = off, at creases and rims alike).",
         [](const P &p) { return p.creaseAngle; }, [](P &p, double v) { p.creaseAngle = v; }},
        {"FitOffsets", "--fit-offsets", "Fit surfels to the blended surface", ParameterKind::Bool, 1, 0, 1, false,
         false, ParameterAudience::Everyone,
         "Move each surfel along its normal so that the surface the surfels blend into passes through the input "
         "points, keeping each move as SurfelFitOffset (off: each surfel stays on the sampled surface, at its "
         "cluster's centroid moved along the normal to the height of the members around it, or at the centroid for "
         "clusters of fewer than 6 points).",
         [](const P &p) { return p.fitOffsets ? 1.0 : 0.0; }, [](P &p, double v) { p.fitOffsets = v != 0; }},
        {"ColorizeClusters", nullptr, "Colour input by cluster", ParameterKind::Bool, 0, 0, 1, false, false,
         ParameterAudience::Everyone, "Give every cluster a random colour on the input layer, to inspect the clustering.",
         nullptr, nullptr},
        {"PropagationDepth", "--depth", "Propagation depth", ParameterKind::Int, 6, 0, unbounded, false, false,
         ParameterAudience::Expert, "Hops a cluster label may travel from its seed point (the paper's depth; 0 = no limit).",
         [](const P &p) { return double(p.propagationDepth); }, [](P &p, double v) { p.propagationDepth = int(v); }},
        {"NormalizationThreshold", "--threshold", "Normalization threshold", ParameterKind::Float, 6, 1, unbounded, true,
         false, ParameterAudience::Expert,
         "Clusters whose positions' covariance has lambda1/lambda2 above it are split through the centroid (the "
         "paper's threshold).",
         [](const P &p) { return p.normalizationThreshold; }, [](P &p, double v) { p.normalizationThreshold = v; }},
        {"WeightWidth", "--weight-width", "Normal weight width (h)", ParameterKind::Float, 0, 0, unbounded, false, false,
         ParameterAudience::Expert,
         "Width h, in model units, of the Gaussian weights blending a cluster's normals into its surfel's normal "
         "(0 = 1 % of the bounding-box diagonal).",
         [](const P &p) { return p.weightWidth; }, [](P &p, double v) { p.weightWidth = v; }},
        {"MaxClusterSize", "--max-cluster-size", "Largest cluster", ParameterKind::Int, 32, 0, unbounded, false,
         false, ParameterAudience::Expert,
         "Clusters of more points are split whatever their shape (0 = off); lower caps give more, smaller surfels "
         "on flat parts; caps below 8 are approximate (lone points rejoin clusters after the splits).",
         [](const P &p) { return double(p.tuning.maxClusterSize); },
         [](P &p, double v) { p.tuning.maxClusterSize = int(v); }},
        {"MaxErrorExchanges", "--exchanges", "Exchanges for the largest error", ParameterKind::Int, 16, 0, 100000,
         false, false, ParameterAudience::Expert,
         "With a target or SpreadEvenly: at most this many exchanges of clusters (split one at the worst point, "
         "merge a similar pair elsewhere) that lower the largest distance to the blended surface at the same count "
         "(0 = off).",
         [](const P &p) { return double(p.maxErrorExchanges); }, [](P &p, double v) { p.maxErrorExchanges = int(v); }},
        {"SpreadEvenly", "--spread-evenly", "Spread evenly, for surface reconstruction", ParameterKind::Bool, 0, 0, 1,
         false, false, ParameterAudience::Expert,
         "For surface reconstruction (Screened Poisson): as many surfels as the level or the target gives, grown "
         "from single points by merging similar neighbours into clusters of even extent, so they spread evenly over "
         "flat parts and stay dense at creases; not with MaxError.",
         [](const P &p) { return p.spreadEvenly ? 1.0 : 0.0; }, [](P &p, double v) { p.spreadEvenly = v != 0; }},
    };
    return table;
}

/// The MeshLab filters the table serves: the same resampler, two purposes.
enum class ResamplingFilter
{
    FeatureSensitive, ///< the paper's output, for rendering and inspection
    ForReconstruction ///< SpreadEvenly set: points meant for surface reconstruction
};

/// The filter's name in MeshLab's menu and in .mlx scripts.
inline const char *FilterTitle(ResamplingFilter filter)
{
    return filter == ResamplingFilter::FeatureSensitive ? "Gaussian Sphere Feature-Sensitive Resampling"
                                                        : "Gaussian Sphere Resampling for Surface Reconstruction";
}

/// Whether `filter`'s dialog shows `spec`: the parameters for everyone, but MaxError, which
/// SpreadEvenly refuses, not in the reconstruction filter's. The others keep their defaults.
inline bool InDialog(const ParameterSpec &spec, ResamplingFilter filter)
{
    return spec.audience == ParameterAudience::Everyone &&
           !(filter == ResamplingFilter::ForReconstruction && std::string(spec.name) == "MaxError");
}

/// The table's entry named `name`, or null.
inline const ParameterSpec *FindParameter(const std::string &name)
{
    for (const ParameterSpec &spec : ParameterTable())
        if (name == spec.name) return &spec;
    return nullptr;
}

inline std::string ResamplingParams::Validate() const
{
    for (const ParameterSpec &spec : ParameterTable())
        if (spec.get != nullptr && !spec.Accepts(spec.get(*this)))
            return std::string(spec.name) + " must be " + spec.RangeText();
    if (spreadEvenly && maxErrorFraction > 0) return "SpreadEvenly takes its count from the level or a target, not from MaxError";
    if (exchangeRounds < -1) return "exchangeRounds must be -1 (all of maxErrorExchanges) or at least 0";
    if (countedVertices < 0) return "countedVertices must be at least 0";
    if (reportHighestAtCreaseFit < 0) return "reportHighestAtCreaseFit must be at least 0";
    if (creaseFitLimits.given && !(creaseFitLimits.distance >= 0 && creaseFitLimits.normalError >= 0))
        return "creaseFitLimits must not be negative";
    if (!surroundingSurfels.empty() && countedVertices == 0)
        return "surroundingSurfels stand beside the counted vertices: countedVertices must be given";
    if (!(seamTarget >= 0)) return "seamTarget must not be negative";
    return tuning.Validate();
}

} // namespace gaussphere
} // namespace vcg

#endif
