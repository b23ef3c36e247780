// The regular grid of cubic tiles over the input's bounding box, and how its edge is chosen.
//
// Core boxes are half-open, [origin + i edge, origin + (i + 1) edge) on each axis, with the last
// tile of an axis closed at the box's maximum: every point lies in exactly one core. A tile's
// halo is the points of other tiles within `halo` of its core box (per axis, so the box grown by
// `halo`); the resampler sees core and halo, and the tile keeps the surfels it owns (tile_run.h).
#ifndef GSTILE_TILE_GRID_H
#define GSTILE_TILE_GRID_H

#include <array>
#include <cstdint>
#include <vector>

namespace gstile {

typedef std::array<int, 3> GridCell;

struct TileGrid
{
    std::array<double, 3> origin{};
    double edge = 1;
    GridCell dims{{1, 1, 1}};

    int TileCount() const { return dims[0] * dims[1] * dims[2]; }
    /// Tiles are numbered with x fastest.
    int IdOf(const GridCell &cell) const { return cell[0] + dims[0] * (cell[1] + dims[1] * cell[2]); }
    GridCell CellOfId(int id) const { return {{id % dims[0], id / dims[0] % dims[1], id / (dims[0] * dims[1])}}; }
    /// The tile whose core holds `p`.
    GridCell CellOf(const float p[3]) const;
    /// Calls visit(id) for every tile but `home` whose core box grown by `halo` holds `p`.
    template <class Visit>
    void ForHaloTiles(const float p[3], double halo, const GridCell &home, Visit visit) const
    {
        GridCell lo, hi;
        for (int a = 0; a < 3; ++a) {
            lo[a] = Clamp(a, (double(p[a]) - halo - origin[a]) / edge);
            hi[a] = Clamp(a, (double(p[a]) + halo - origin[a]) / edge);
        }
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x)
                    if (x != home[0] || y != home[1] || z != home[2]) visit(IdOf({{x, y, z}}));
    }
    /// floor(t) on axis `a`, within the grid.
    int Clamp(int a, double t) const;
};

/// Point counts in the cells of a fine grid over the bounding box (kCellsOnLongestSide cells on
/// its longest side), read back over boxes of cells through prefix sums: what the choice of the
/// tile edge needs. Filled from a uniform sample, each point standing for `weight` input points.
class OccupancyHistogram
{
public:
    static constexpr int kCellsOnLongestSide = 128;

    OccupancyHistogram(const std::array<double, 3> &boxMin, const std::array<double, 3> &boxMax);
    void Add(const float p[3]);
    /// Call once, after the last Add.
    void Finish(double weight);
    /// Input points in the cells [lo, hi) (clamped to the grid).
    double CountIn(GridCell lo, GridCell hi) const;
    const TileGrid &Cells() const { return cells_; }

private:
    std::size_t Index(int x, int y, int z) const;
    TileGrid cells_;
    std::vector<double> sums_; // (dims + 1)^3 prefix sums; sample counts until Finish
};

struct TileGridChoice
{
    TileGrid grid;
    double largestTilePoints = 0; ///< core + halo of the fullest tile, as the histogram estimates it
    bool fits = false;            ///< largestTilePoints <= the tile points asked for
};

/// The coarsest grid (largest edge, a whole number of histogram cells) whose fullest tile holds at
/// most `tilePoints` points with its halo. Tiles are never narrower than the halo: a narrower
/// tile would mostly resample its halo, and copy each point into dozens of halos (more than the
/// 26 neighbours of a cube). When even such tiles are too full, the grid of the narrowest, not
/// `fits`.
TileGridChoice ChooseTileGrid(const OccupancyHistogram &histogram, double halo, double tilePoints);

} // namespace gstile

#endif
