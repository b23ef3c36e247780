// The level search of a target count (size_control/level_search.h), on counts given by hand.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include <vcg_ext/gaussphere/size_control/level_search.h>

using vcg::gaussphere::LevelSearch;

namespace {

/// The levels the search asks for, given the count at each level, and the level it ends with.
std::vector<int> Search(std::uint64_t target, int start, std::uint64_t (*count)(int), double mergeWithin, int &chosen)
{
    LevelSearch search(target, start);
    std::vector<int> asked;
    while (const int level = search.Next()) {
        asked.push_back(level);
        search.Tell(count(level));
    }
    chosen = search.Level(mergeWithin);
    return asked;
}

std::uint64_t TenPerLevel(int level) { return std::uint64_t(10 * level); }

TEST(LevelSearch, DoublesThenBisectsToTheFinestLevelThatFits)
{
    int chosen = 0;
    EXPECT_EQ(Search(205, 8, TenPerLevel, 1.0, chosen), (std::vector<int>{8, 16, 32, 24, 20, 22, 21}));
    EXPECT_EQ(chosen, 20);
    EXPECT_EQ(Search(45, 8, TenPerLevel, 1.0, chosen), (std::vector<int>{8, 4, 6, 5}));
    EXPECT_EQ(chosen, 4);
}

TEST(LevelSearch, MergesFromTheNextLevelWhenItIsNearTheTarget)
{
    int chosen = 0;
    LevelSearch near(45, 8);
    for (const int level : {8, 4, 6, 5}) {
        ASSERT_EQ(near.Next(), level);
        near.Tell(TenPerLevel(level));
    }
    EXPECT_EQ(near.Next(), 0);
    EXPECT_FALSE(near.Merges(1.0)) << "50 is 1.11 x 45";
    EXPECT_TRUE(near.Merges(1.15));
    EXPECT_EQ(near.Level(1.15), 5);
    EXPECT_EQ(Search(5, 8, TenPerLevel, 1.0, chosen), (std::vector<int>{8, 4, 2}));
    EXPECT_EQ(chosen, 2) << "even level 2 gives too many: merged down from it";
    EXPECT_EQ(Search(100000, 200, TenPerLevel, 1.0, chosen), (std::vector<int>{200, 256}));
    EXPECT_EQ(chosen, 256) << "the finest level gives too few: split up from it";
}

} // namespace
