#include "tile_grid.h"

#include <algorithm>
#include <cmath>

namespace gstile {

constexpr int OccupancyHistogram::kCellsOnLongestSide; // C++14: its odr-uses (std::min) need a definition

int TileGrid::Clamp(int a, double t) const
{
    if (!(t > 0)) return 0;
    return int(std::min(std::floor(t), double(dims[a] - 1)));
}

GridCell TileGrid::CellOf(const float p[3]) const
{
    GridCell cell;
    for (int a = 0; a < 3; ++a) cell[a] = Clamp(a, (double(p[a]) - origin[a]) / edge);
    return cell;
}

OccupancyHistogram::OccupancyHistogram(const std::array<double, 3> &boxMin, const std::array<double, 3> &boxMax)
{
    double longest = 0;
    for (int a = 0; a < 3; ++a) longest = std::max(longest, boxMax[a] - boxMin[a]);
    cells_.origin = boxMin;
    cells_.edge = longest > 0 ? longest / kCellsOnLongestSide : 1.0;
    for (int a = 0; a < 3; ++a)
        cells_.dims[a] = std::max(1, std::min(kCellsOnLongestSide, int(std::ceil((boxMax[a] - boxMin[a]) / cells_.edge))));
    sums_.assign(std::size_t(cells_.dims[0] + 1) * (cells_.dims[1] + 1) * (cells_.dims[2] + 1), 0);
}

std::size_t OccupancyHistogram::Index(int x, int y, int z) const
{
    return std::size_t(x) + std::size_t(cells_.dims[0] + 1) * (std::size_t(y) + std::size_t(cells_.dims[1] + 1) * z);
}

void OccupancyHistogram::Add(const float p[3])
{
    const GridCell c = cells_.CellOf(p);
    ++sums_[Index(c[0] + 1, c[1] + 1, c[2] + 1)];
}

void OccupancyHistogram::Finish(double weight)
{
    for (double &count : sums_) count *= weight;
    const GridCell &d = cells_.dims;
    for (int z = 1; z <= d[2]; ++z)
        for (int y = 1; y <= d[1]; ++y)
            for (int x = 1; x <= d[0]; ++x)
                sums_[Index(x, y, z)] += sums_[Index(x - 1, y, z)] + sums_[Index(x, y - 1, z)] +
                                         sums_[Index(x, y, z - 1)] - sums_[Index(x - 1, y - 1, z)] -
                                         sums_[Index(x - 1, y, z - 1)] - sums_[Index(x, y - 1, z - 1)] +
                                         sums_[Index(x - 1, y - 1, z - 1)];
}

double OccupancyHistogram::CountIn(GridCell lo, GridCell hi) const
{
    for (int a = 0; a < 3; ++a) {
        lo[a] = std::max(0, std::min(lo[a], cells_.dims[a]));
        hi[a] = std::max(lo[a], std::min(hi[a], cells_.dims[a]));
    }
    return sums_[Index(hi[0], hi[1], hi[2])] - sums_[Index(lo[0], hi[1], hi[2])] - sums_[Index(hi[0], lo[1], hi[2])] -
           sums_[Index(hi[0], hi[1], lo[2])] + sums_[Index(lo[0], lo[1], hi[2])] + sums_[Index(lo[0], hi[1], lo[2])] +
           sums_[Index(hi[0], lo[1], lo[2])] - sums_[Index(lo[0], lo[1], lo[2])];
}

namespace {

/// The fullest tile of tiles `span` histogram cells wide, halo included (`haloCells` cells, rounded up).
double LargestTile(const OccupancyHistogram &histogram, int span, int haloCells, TileGrid &grid)
{
    const TileGrid &cells = histogram.Cells();
    grid.origin = cells.origin;
    grid.edge = cells.edge * span;
    for (int a = 0; a < 3; ++a) grid.dims[a] = (cells.dims[a] + span - 1) / span;
    double largest = 0;
    for (int id = 0; id < grid.TileCount(); ++id) {
        const GridCell t = grid.CellOfId(id);
        GridCell lo, hi;
        for (int a = 0; a < 3; ++a) {
            lo[a] = t[a] * span - haloCells;
            hi[a] = (t[a] + 1) * span + haloCells;
        }
        largest = std::max(largest, histogram.CountIn(lo, hi));
    }
    return largest;
}

} // namespace

TileGridChoice ChooseTileGrid(const OccupancyHistogram &histogram, double halo, double tilePoints)
{
    const int haloCells = int(std::ceil(halo / histogram.Cells().edge));
    const int narrowest = std::max(1, std::min(haloCells, OccupancyHistogram::kCellsOnLongestSide));
    TileGridChoice choice;
    for (int span = OccupancyHistogram::kCellsOnLongestSide; span >= narrowest; --span) {
        choice.largestTilePoints = LargestTile(histogram, span, haloCells, choice.grid);
        choice.fits = choice.largestTilePoints <= tilePoints;
        if (choice.fits) break;
    }
    return choice;
}

} // namespace gstile
