// Beyond the paper: the Gaussian sphere level a target count starts from.
//
// The count grows with the level. The search takes the finest level in [2, 256] whose count
// stays at or below the target (doubling from a start level, then bisection), whose clusters
// splitting brings up to the target; or, when the next finer level gives at most mergeWithin
// times the target, or even level 2 gives more, that level, whose clusters merging brings down to
// it: merging a finer level's most similar neighbours keeps its small clusters at creases.
//
// The search only sees counts, one level at a time, so that whoever has them can drive it: the
// resampler clusters each level it asks for (resampling.h), a tiled run sums the tiles' counts
// (tools/gstile/target_share.h) and so takes the level the whole input would.
#ifndef VCG_EXT_GAUSSPHERE_LEVEL_SEARCH_H
#define VCG_EXT_GAUSSPHERE_LEVEL_SEARCH_H

#include <algorithm>
#include <cstdint>

namespace vcg {
namespace gaussphere {

class LevelSearch
{
public:
    enum : int { kMinLevel = 2, kMaxLevel = 256 }; // not static members: C++14 would need their definitions

    /// \pre target >= 1, startLevel in [kMinLevel, kMaxLevel].
    LevelSearch(std::uint64_t target, int startLevel) : target_(target), next_(startLevel) {}

    /// The level whose count the search needs next, or 0 when it is over.
    int Next() const { return next_; }

    /// The count of Next(); true when that level is now the one to split from, false when it is
    /// now the coarsest known to give too many (the one to merge from).
    bool Tell(std::uint64_t count)
    {
        const int level = next_;
        const bool fits = count <= target_;
        if (fits && level > good_) good_ = level;
        if (!fits && (bad_ == 0 || level < bad_)) {
            bad_ = level;
            badCount_ = count;
        }
        next_ = Following();
        return fits;
    }

    /// Once the search is over: the level chosen, and whether its clusters merge down to the
    /// target (else they split up to it, or are as many).
    int Level(double mergeWithin) const { return Merges(mergeWithin) ? bad_ : good_; }
    bool Merges(double mergeWithin) const
    {
        return bad_ != 0 && (good_ == 0 || double(badCount_) <= mergeWithin * double(target_));
    }

private:
    int Following() const
    {
        if (good_ != 0 && bad_ != 0) return bad_ - good_ <= 1 ? 0 : (good_ + bad_) / 2;
        if (good_ != 0) return good_ == kMaxLevel ? 0 : std::min<int>(kMaxLevel, 2 * good_);
        return bad_ == kMinLevel ? 0 : std::max<int>(kMinLevel, bad_ / 2);
    }

    std::uint64_t target_;
    int next_;
    int good_ = 0, bad_ = 0;      ///< finest level known to fit, coarsest known not to
    std::uint64_t badCount_ = 0;  ///< the count of bad_
};

} // namespace gaussphere
} // namespace vcg

#endif
