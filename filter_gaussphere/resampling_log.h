// The filter's log: the lines a MeshLab user reads after a run, as plain text, so that every
// host adapter of the filter prints the same figures. Qt-free.
#ifndef FILTER_GAUSSPHERE_RESAMPLING_LOG_H
#define FILTER_GAUSSPHERE_RESAMPLING_LOG_H

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <string>
#include <vector>

#include <vcg_ext/gaussphere/resampling.h>

namespace gaussphere_filter {

struct LogLine
{
    bool warning;
    std::string text;
};

inline std::string Format(const char *format, ...) __attribute__((format(printf, 1, 2)));
inline std::string Format(const char *format, ...)
{
    char text[512];
    va_list args;
    va_start(args, format);
    std::vsnprintf(text, sizeof text, format, args);
    va_end(args);
    return text;
}

/// The figures of a run: counts and times, then what the size control did, then what was skipped.
inline std::vector<LogLine> RunLog(const vcg::gaussphere::ResamplingStats &s)
{
    using vcg::gaussphere::SizeControl;
    std::vector<LogLine> log;
    const int used = s.inputCount - s.skippedCount;
    log.push_back({false, Format("Gaussian sphere resampling: %d points -> %d surfels (%.2f%%), level %d, %d iteration(s), "
                                 "%.1f adaptive neighbours per point, L2,1 RMS %.4f; time %.3f s on %d thread(s) "
                                 "(neighbours %.3f, propagation %.3f, normalization %.3f, refinement %.3f, surfels %.3f, "
                                 "exchanges %.3f)",
                                 used, s.outputCount, 100.0 * s.outputCount / std::max(1, used), s.levelUsed, s.iterations,
                                 s.meanAdaptiveNeighbors, s.normalErrorRms, s.TotalSeconds(), s.threadsUsed,
                                 s.secondsNeighbors, s.secondsPropagation, s.secondsNormalization, s.secondsRefinement,
                                 s.secondsSurfels, s.secondsExchanges)});
    if (s.surfelsNarrowedAtCreases > 0)
        log.push_back({false, Format("Gaussian sphere resampling: %d surfel(s) around creases blend narrower",
                                     s.surfelsNarrowedAtCreases)});
    if (s.rimPoints > 0)
        log.push_back({false, Format("Gaussian sphere resampling: %d point(s) on the rim of an open surface: their "
                                     "clusters are kept small, as at creases",
                                     s.rimPoints)});
    if (s.straySplits > 0)
        log.push_back({false, Format("Gaussian sphere resampling: %d cluster(s) beside creases split for a member nearer "
                                     "to other clusters than to its own",
                                     s.straySplits)});
    if (s.boundaryPoints > 0)
        log.push_back({false, Format("Gaussian sphere resampling: %d point(s) on or beside the rim of an open surface: "
                                     "their surfels are not fitted",
                                     s.boundaryPoints)});
    if (s.surfelsFitted > 0)
        log.push_back({false, Format("Gaussian sphere resampling: %d surfel(s) fitted to the blended surface (longest "
                                     "move %g = %.5f x diagonal)",
                                     s.surfelsFitted, s.largestFitMove * s.diagonal, s.largestFitMove)});
    if (s.sizeMode == SizeControl::TargetCount) {
        log.push_back({false, Format("Gaussian sphere resampling: target %d: level %d chosen after %d tried, %d split(s), "
                                     "%d merge(s)",
                                     s.targetCount, s.levelUsed, s.levelsTried, s.splitsForTarget, s.mergesForTarget)});
        if (s.exchangeTrials > 0)
            log.push_back({false, Format("Gaussian sphere resampling: %d exchange(s) of clusters kept of %d tried, largest "
                                         "distance to the blended surface %.3g -> %.3g x diagonal, then %d surfel(s) at "
                                         "creases fitted to the blend (%.3f s)",
                                         s.exchangesForMaxError, s.exchangeTrials, s.exchangeMaxBefore, s.exchangeMaxAfter,
                                         s.creaseFitsForMaxError, s.secondsExchanges)});
        const std::string miss = s.TargetMissReason();
        if (!miss.empty())
            log.push_back({true, Format("Gaussian sphere resampling: %d surfels instead of the %d requested: %s",
                                        s.outputCount, s.targetCount, miss.c_str())});
    }
    if (s.sizeMode == SizeControl::ErrorBound) {
        log.push_back({false, Format("Gaussian sphere resampling: error bound: %d + %d split(s) (own planes + blended "
                                     "surface), %d halving(s) of one-point surfels' blend scales, %d projection round(s)",
                                     s.splitsForErrorBound, s.splitsForSurfaceBound, s.narrowingsForSurfaceBound,
                                     s.surfaceBoundRounds)});
        if (s.pointsAboveErrorBound == 0)
            log.push_back({false, Format("Gaussian sphere resampling: error bound met: largest distance to the blended "
                                         "surface %g = %.5f x diagonal",
                                         s.surfaceErrorMax * s.diagonal, s.surfaceErrorMax)});
        else
            log.push_back({true, Format("Gaussian sphere resampling: error bound: %d point(s) remain beyond it (largest "
                                        "%g = %.5f x diagonal): %s",
                                        s.pointsAboveErrorBound, s.surfaceErrorMax * s.diagonal, s.surfaceErrorMax,
                                        s.ErrorBoundMissReason().c_str())});
    }
    if (s.coincidentPoints > 0)
        log.push_back({false, Format("Gaussian sphere resampling: %d point(s) lie at the position of another point "
                                     "facing the same side and count once, in its surfel", s.coincidentPoints)});
    if (s.skippedNormals > 0)
        log.push_back({true, Format("Gaussian sphere resampling skipped %d point(s) with a zero or invalid normal",
                                    s.skippedNormals)});
    if (s.skippedPositions > 0)
        log.push_back({true, Format("Gaussian sphere resampling skipped %d point(s) with a non-finite position",
                                    s.skippedPositions)});
    const std::string coarse = s.CoarsePositionsReason();
    if (!coarse.empty()) log.push_back({true, "Gaussian sphere resampling: " + coarse});
    return log;
}

} // namespace gaussphere_filter

#endif
