// The resampler's surfels of a clustering, made whole or updated where a few clusters changed.
//
// A clustering becomes surfels in three steps: one surfel per cluster (GenerateSurfels), narrower
// blends around creases (NarrowBlendsAroundCreases), offsets fitted to the blend
// (FitSurfelOffsets). The exchanges of max_error_exchange.h try hundreds of clusterings that
// differ from the current one in two or three clusters; making every surfel anew for each would
// be most of their time and grow with the input. SurfelMaker::Update redoes only what a change
// reaches: the surfels of the changed clusters, and the fits of the clusters whose sampled
// members blend a changed cluster's surfel; the result equals Make's (a test compares them).
#ifndef VCG_EXT_GAUSSPHERE_SURFEL_RECIPE_H
#define VCG_EXT_GAUSSPHERE_SURFEL_RECIPE_H

#include <algorithm>
#include <functional>
#include <utility>
#include <vector>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/clustering/clustering.h>
#include <vcg_ext/gaussphere/surfels/crease_blend.h>
#include <vcg_ext/gaussphere/surfels/surfel_generation.h>
#include <vcg_ext/gaussphere/surfels/surfel_offset.h>

namespace vcg {
namespace gaussphere {

struct SurfelRecipe
{
    SurfelGenerationParams generation;          ///< blendScale must stay null
    float creaseBlendScale = 1.f;               ///< NarrowBlendsAroundCreases' scale (1: off)
    bool fitOffsets = false;                    ///< FitSurfelOffsets (without a plane bound)
    const FlatVector<char> *pinnedPoints = nullptr; ///< clusters holding one are not fitted (crease points;
                                                    ///< with SpreadEvenly boundary points too)
    const FlatVector<char> *boundaryPoints = nullptr; ///< of those, clusters holding one stay unfitted at the
                                                      ///< crease fit after the exchanges too (CreaseMoves)
};

/// The surfels of `clusters` (members = ClusterMembers(clusters)) by `recipe` before the fit:
/// generated, blends narrowed around creases.
inline std::vector<Surfel> UnfittedSurfels(const PointArray &points, const PointArray &normals,
                                           const NeighborGraph &graph, const Clustering &clusters,
                                           const ClusterMembers &members, const SurfelRecipe &recipe)
{
    std::vector<Surfel> surfels = GenerateSurfels(points, normals, graph.spacing, clusters, members, recipe.generation);
    NarrowBlendsAroundCreases(graph, clusters, recipe.creaseBlendScale, surfels);
    return surfels;
}

/// The surfels of `clusters` by `recipe`, fitted in place (no copy of the unfitted ones: at 20
/// million points the surfel stage is where the memory peaks). `beforeFit`, if given, is called
/// between generation and fit (each takes about a second at 20 million points: a progress report).
inline std::vector<Surfel> MakeSurfels(const PointArray &points, const PointArray &normals, const NeighborGraph &graph,
                                       const Clustering &clusters, const SurfelRecipe &recipe,
                                       const std::function<void()> &beforeFit = nullptr)
{
    const ClusterMembers members(clusters); // built once for both steps
    std::vector<Surfel> surfels = UnfittedSurfels(points, normals, graph, clusters, members, recipe);
    if (recipe.fitOffsets) {
        if (beforeFit) beforeFit();
        FitSurfelOffsets(points, normals, graph, clusters, members, recipe.pinnedPoints, surfels);
    }
    return surfels;
}

/// MakeSurfels, keeping the unfitted surfels beside the fitted ones so that a clustering that
/// differs in a few clusters can be updated (Update).
class SurfelMaker
{
public:
    /// A clustering's surfels before and after the fit (the fit reads the unfitted ones).
    struct Set
    {
        std::vector<Surfel> unfitted, fitted;
    };

    /// \pre points, unit normals and `graph` as clustered; they outlive the maker. Later, the
    ///      graph may keep only its first kOffsetNeighbors slots (KeepFirstSlots): the maker
    ///      reads no further.
    SurfelMaker(const PointArray &points, const PointArray &normals, const NeighborGraph &graph,
                const SurfelRecipe &recipe)
        : points_(points), normals_(normals), graph_(graph), recipe_(recipe),
          narrowing_(NarrowingFlags(graph, recipe.creaseBlendScale))
    {}

    /// MakeSurfels(clusters) on the graph the maker was made with: the fitted surfels alone, fitted
    /// in place. `beforeFit`, if given, is called between generation and fit (a progress report).
    std::vector<Surfel> MakeFitted(const Clustering &clusters, const std::function<void()> &beforeFit = nullptr) const
    {
        const ClusterMembers members(clusters);
        std::vector<Surfel> surfels = Unfitted(clusters, members);
        if (recipe_.fitOffsets) {
            if (beforeFit) beforeFit();
            FitSurfelOffsets(points_, normals_, graph_, clusters, members, recipe_.pinnedPoints, surfels);
        }
        return surfels;
    }

    /// `beforeFit`, if given, is called between generation and fit (a progress report; also when
    /// the recipe fits nothing); when it returns false the fit is skipped (a cancel: seconds at
    /// tens of millions of points) and the set's fitted surfels are the unfitted ones.
    Set Make(const Clustering &clusters, const std::function<bool()> &beforeFit = nullptr) const
    {
        Set s;
        const ClusterMembers members(clusters);
        s.unfitted = Unfitted(clusters, members);
        const bool fit = !beforeFit || beforeFit();
        s.fitted = s.unfitted;
        if (fit && recipe_.fitOffsets)
            FitSurfelOffsets(points_, normals_, graph_, clusters, members, recipe_.pinnedPoints, s.fitted);
        return s;
    }

    /// Make(trial), from base = Make(baseClusters) and baseMembers = ClusterMembers(baseClusters),
    /// where trial differs from baseClusters only in the members of the clusters `dirty` (an index
    /// may be one past baseClusters' last, a new cluster); dirtyMembers[j] holds the members of
    /// dirty[j] in trial, in increasing order. The base labels are not needed: a point whose
    /// cluster changed is in a dirty cluster both before and after, so the caller may have
    /// turned baseClusters into trial in place.
    Set Update(const Set &base, const ClusterMembers &baseMembers, const Clustering &trial,
               const std::vector<int> &dirty, const std::vector<std::vector<int>> &dirtyMembers) const
    {
        Set s;
        Update(base, baseMembers, trial, dirty, dirtyMembers, s);
        return s;
    }
    /// The same into `s` (not `base`), reusing its buffers.
    void Update(const Set &base, const ClusterMembers &baseMembers, const Clustering &trial,
                const std::vector<int> &dirty, const std::vector<std::vector<int>> &dirtyMembers, Set &s) const
    {
        const int count = trial.clusterCount, baseCount = int(baseMembers.offset.size()) - 1;
        s.unfitted = base.unfitted;
        s.unfitted.resize(size_t(count));
        std::vector<int> dirtyIndex(size_t(std::max(count, baseCount)), -1);
        for (size_t j = 0; j < dirty.size(); ++j) {
            const int c = dirty[j];
            dirtyIndex[size_t(c)] = int(j);
            const std::vector<int> &m = dirtyMembers[j];
            Surfel &surfel = s.unfitted[size_t(c)];
            surfel = MakeSurfel(points_, normals_, graph_.spacing, m.data(), m.data() + m.size(), recipe_.generation);
            if (!narrowing_.empty() && m.size() >= 2 &&
                std::any_of(m.begin(), m.end(), [this](int i) { return bool(narrowing_[size_t(i)]); }))
                surfel.blendScale = recipe_.creaseBlendScale;
        }
        s.fitted = base.fitted;
        s.fitted.resize(size_t(count));
        for (int c : dirty) s.fitted[size_t(c)] = s.unfitted[size_t(c)];
        if (!recipe_.fitOffsets) return;

        // Clusters to fit again: the changed ones, and those a sampled member of which has among
        // its blended neighbour slots a point of a changed cluster (before or after the change:
        // the same clusters, see above).
        auto changed = [&](int point) {
            const int after = trial.label[point];
            return after >= 0 && dirtyIndex[size_t(after)] >= 0;
        };
        std::vector<char> reached(size_t(baseCount), 0);
#pragma omp parallel for schedule(static)
        for (int c = 0; c < baseCount; ++c) {
            if (dirtyIndex[size_t(c)] >= 0) continue;
            ForEachOffsetSample(baseMembers.begin(c), baseMembers.end(c), [&](int i) {
                const int *q = graph_.begin(i), *end = q + std::min<int>(graph_.found[i], kOffsetNeighbors);
                for (; q != end && !reached[size_t(c)]; ++q) reached[size_t(c)] = changed(*q);
            });
        }
        std::vector<int> refit(dirty);
        for (int c = 0; c < baseCount; ++c)
            if (reached[size_t(c)]) refit.push_back(c);
        auto weightOf = [&s](int l) { return BlendWeight(s.unfitted[size_t(l)]); };
        std::vector<float> offset(refit.size());
#pragma omp parallel for schedule(dynamic, 16)
        for (int t = 0; t < int(refit.size()); ++t) {
            const int c = refit[size_t(t)];
            const int j = dirtyIndex[size_t(c)];
            const int *begin = j >= 0 ? dirtyMembers[size_t(j)].data() : baseMembers.begin(c);
            const int *end = j >= 0 ? begin + dirtyMembers[size_t(j)].size() : baseMembers.end(c);
            offset[size_t(t)] = SurfelOffsetOf(points_, normals_, graph_, trial.label, recipe_.pinnedPoints, s.unfitted,
                                               weightOf, c, begin, end, 0.0);
        }
        for (size_t t = 0; t < refit.size(); ++t) {
            Surfel &surfel = s.fitted[size_t(refit[t])];
            surfel = s.unfitted[size_t(refit[t])];
            MoveSurfel(surfel, offset[t]);
        }
    }

    /// The moves FitSurfelOffsets would give the surfels of `set` (= Make(clusters), members =
    /// ClusterMembers(clusters)) that it leaves at creases (StaysAtCrease), for the clusters of at
    /// least minMembers members: (cluster, move) for every non-zero move, clusters ascending.
    /// Empty when the recipe fits nothing. Each move reads the unfitted surfels only, so the moves
    /// of any subset may be applied to set.fitted together.
    std::vector<std::pair<int, float>> CreaseMoves(const Set &set, const Clustering &clusters,
                                                   const ClusterMembers &members, int minMembers) const
    {
        std::vector<std::pair<int, float>> moves;
        if (!recipe_.fitOffsets) return moves;
        const int count = clusters.clusterCount;
        std::vector<float> offset(size_t(count), 0.f);
        auto weightOf = [&set](int l) { return BlendWeight(set.unfitted[size_t(l)]); };
#pragma omp parallel for schedule(dynamic, 64)
        for (int c = 0; c < count; ++c) {
            if (members.Size(c) < std::max(1, minMembers) ||
                !StaysAtCrease(recipe_.pinnedPoints, set.unfitted, c, members.begin(c), members.end(c)) ||
                (recipe_.boundaryPoints && members.AnyFlagged(c, *recipe_.boundaryPoints)))
                continue;
            offset[size_t(c)] = SurfelOffsetOf(points_, normals_, graph_, clusters.label, recipe_.pinnedPoints,
                                               set.unfitted, weightOf, c, members.begin(c), members.end(c), 0.0, true);
        }
        for (int c = 0; c < count; ++c)
            if (offset[size_t(c)] != 0) moves.push_back({c, offset[size_t(c)]});
        return moves;
    }

private:
    /// UnfittedSurfels, the blends narrowed from the flags: the graph's rows beyond the fit's
    /// slots may be gone.
    std::vector<Surfel> Unfitted(const Clustering &clusters, const ClusterMembers &members) const
    {
        std::vector<Surfel> surfels = GenerateSurfels(points_, normals_, graph_.spacing, clusters, members, recipe_.generation);
        NarrowFlaggedBlends(narrowing_, clusters, recipe_.creaseBlendScale, surfels);
        return surfels;
    }

    const PointArray &points_, &normals_;
    const NeighborGraph &graph_;
    SurfelRecipe recipe_;
    std::vector<bool> narrowing_; // a bit a point: it lives through the surfels' stage
};

} // namespace gaussphere
} // namespace vcg

#endif
