// Finding the parameter at which a peer method outputs a given number of points.
//
// Every comparison in the benchmark is made at equal output counts: our resampler fixes the
// count (through the Gaussian sphere level n) and each peer is tuned to it. The peers'
// counts are monotone in their parameter (cell size, disk radius, cluster size or
// variation) but not continuous, so one safeguarded search serves them all.
#ifndef GSBENCH_MATCH_COUNT_H
#define GSBENCH_MATCH_COUNT_H

#include <functional>

namespace gsbench {

enum class SearchDomain
{
    Positive, ///< any positive real: cell size, radius, variation threshold
    Integer,  ///< positive integers: maximum cluster size
};

struct CountMatch
{
    double parameter = 0;   ///< the evaluated parameter whose count is closest to the target
    int count = 0;          ///< its count
    int evaluations = 0;    ///< calls of countAt, endpoints included
    bool withinTolerance = false;
    /// The tightest bracket seen: a parameter giving more points than the target and one giving
    /// fewer (0 when no such parameter was evaluated). A two-stage search continues from them.
    double parameterAbove = 0, parameterBelow = 0;
};

/// Searches [lo, hi] for a parameter p with |countAt(p) - target| <= tolerance * target.
/// countAt must be monotone (either way) in p over the bracket, and the bracket should contain
/// the target (if it does not, the nearer endpoint is returned with withinTolerance = false).
///
/// The step is interpolated in log(parameter) against log(count), because all the peers'
/// counts follow a power law of their parameter (count ~ cell size^-2 for a surface); that
/// needs 3-5 evaluations where plain bisection needs ~10, which matters when one evaluation is
/// a meshlabserver run. The interpolated point is kept inside the middle 80 % of the bracket
/// (in log scale) so that a poor fit still shrinks the bracket like a bisection would.
/// If the bracket collapses on a jump of the count without a match, parameters within +-10 %
/// of the best one are tried in 0.5 % steps: counts that are monotone only on average (grid
/// alignment on small models) often land in the band there.
CountMatch MatchCount(const std::function<int(double)> &countAt, double lo, double hi, int target,
                      double tolerance, SearchDomain domain, int maxEvaluations = 60);

} // namespace gsbench

#endif
