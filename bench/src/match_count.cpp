#include "match_count.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace gsbench {

namespace {

struct Sample
{
    double parameter;
    int count;
};

/// Log-log interpolation between two samples for the target, confined to the middle 80 % of
/// the bracket.
double NextParameter(const Sample &a, const Sample &b, int target, SearchDomain domain)
{
    const double la = std::log(a.parameter), lb = std::log(b.parameter);
    double t = 0.5;
    if (a.count > 0 && b.count > 0 && a.count != b.count)
        t = (std::log(double(target)) - std::log(double(a.count))) /
            (std::log(double(b.count)) - std::log(double(a.count)));
    t = std::min(0.9, std::max(0.1, t));
    double p = std::exp(la + t * (lb - la));
    if (domain == SearchDomain::Integer) {
        // Stay strictly inside the bracket, or the search would stall on an endpoint.
        const double lower = std::min(a.parameter, b.parameter), upper = std::max(a.parameter, b.parameter);
        p = std::min(upper - 1, std::max(lower + 1, std::round(p)));
    }
    return p;
}

} // namespace

CountMatch MatchCount(const std::function<int(double)> &countAt, double lo, double hi, int target,
                      double tolerance, SearchDomain domain, int maxEvaluations)
{
    if (!(lo > 0) || !(hi > lo) || target < 1)
        throw std::invalid_argument("MatchCount: needs 0 < lo < hi and a positive target");
    if (domain == SearchDomain::Integer) {
        lo = std::max(1.0, std::round(lo));
        hi = std::max(lo + 1, std::round(hi));
    }
    CountMatch match;
    const int allowed = int(std::floor(tolerance * target));
    int countAbove = 0, countBelow = 0; // counts at match.parameterAbove / parameterBelow
    auto evaluate = [&](double p) {
        const Sample s{p, countAt(p)};
        ++match.evaluations;
        if (match.evaluations == 1 || std::abs(s.count - target) < std::abs(match.count - target)) {
            match.parameter = p;
            match.count = s.count;
        }
        if (s.count > target && (match.parameterAbove == 0 || std::abs(s.count - target) <= std::abs(countAbove - target))) {
            match.parameterAbove = p;
            countAbove = s.count;
        }
        if (s.count < target && (match.parameterBelow == 0 || std::abs(s.count - target) <= std::abs(countBelow - target))) {
            match.parameterBelow = p;
            countBelow = s.count;
        }
        return s;
    };
    Sample a = evaluate(lo), b = evaluate(hi);
    auto done = [&]() { return std::abs(match.count - target) <= allowed; };
    auto bracketed = [&]() { return (a.count - target) * double(b.count - target) <= 0; };
    // A bracket that misses the target is widened on the side that moves toward it (the
    // endpoint whose count is nearer), a factor of 4 at a time.
    for (int widening = 0; !bracketed() && !done() && widening < 4; ++widening) {
        Sample &nearer = std::abs(a.count - target) < std::abs(b.count - target) ? a : b;
        const Sample &other = &nearer == &a ? b : a;
        double p = nearer.parameter > other.parameter ? nearer.parameter * 4 : nearer.parameter / 4;
        if (domain == SearchDomain::Integer) p = std::max(1.0, std::round(p));
        if (p == nearer.parameter) break;
        nearer = evaluate(p);
    }
    while (bracketed() && !done() && match.evaluations < maxEvaluations) {
        // A collapsed bracket: the count jumps over the tolerance band here.
        if (domain == SearchDomain::Integer && std::abs(b.parameter - a.parameter) <= 1) break;
        if (domain == SearchDomain::Positive && std::abs(std::log(b.parameter / a.parameter)) < 1e-3) break;
        const Sample m = evaluate(NextParameter(a, b, target, domain));
        // Keep the half whose ends straddle the target.
        if ((a.count - target) * double(m.count - target) <= 0) b = m;
        else a = m;
    }
    const double bestBeforeScan = match.parameter;
    // Counts that are monotone only on average (a grid's count jumps with the alignment of
    // its cells on small models) can leave a collapsed bracket with no parameter in the
    // tolerance band; parameters near the best one then often land inside it.
    for (int step = 1; domain == SearchDomain::Positive && !done() && match.evaluations < maxEvaluations; ++step) {
        const double offset = 0.005 * ((step + 1) / 2) * (step % 2 ? 1 : -1); // +0.5 %, -0.5 %, +1 %, ...
        if (std::abs(offset) > 0.1) break;
        evaluate(bestBeforeScan * (1 + offset));
    }
    match.withinTolerance = done();
    return match;
}

} // namespace gsbench
