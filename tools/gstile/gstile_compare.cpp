// gstile_compare: a tiled run against the whole run of the same input, for the tests and the
// benchmark (docs/tiling.md, "Checking a tiled run").
//
//   gstile_compare TILEDIR WHOLE.surfel TILED.surfel [BAND]
//
// Prints key=value lines:
//  - counts, and the points the surfels represent (the sum of their qualities);
//  - the error metric of vcg_ext/surfel_error (RMS, max and 99.9th percentile of Δ*, of L2,1 to
//    the nearest surfel and of L2,1 to the blended surface) of both against the input, and their
//    relative differences;
//  - seams, doubles: each surfel's nearest other surfel is "across" when it comes from another
//    tile (tiled: the tile whose result holds it; whole: the tile whose core holds its centre),
//    else "inside"; the medians and 5th percentiles of both distances, whose ratio falls far
//    below 1 where tiles keep the same cluster twice;
//  - seams, holes: the input points within BAND sample spacings (default 3) of a face between
//    two tiles that no surfel's ellipse covers (within the ellipse in its plane and at most a
//    major semi-axis off it), for both outputs.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <io_surfel/surfel_file.h>
#include <vcg_ext/gaussphere/oriented_point_mesh.h>
#include <vcg_ext/surfel_error/surfel_error.h>
#include <tools/gsresample/ply_input.h>

#include "border_points.h"
#include "manifest.h"
#include "point_tree.h"
#include "tile_files.h"

using namespace gstile;
using surfel_io::SurfelRecord;

namespace {

typedef std::array<float, 3> Point;

struct Output
{
    std::vector<SurfelRecord> surfels;
    std::vector<int> tile; ///< per surfel
};

vcg::Point3f P(const surfel_io::Vec3f &v) { return vcg::Point3f(v[0], v[1], v[2]); }

void Require(bool ok, const std::string &error)
{
    if (ok) return;
    std::fprintf(stderr, "gstile_compare: error: %s\n", error.c_str());
    std::exit(1);
}

vcg::gaussphere::metric::SurfelErrorStats Metric(const vcg::gaussphere::OrientedPointMesh &input, const Output &out)
{
    vcg::gaussphere::OrientedPointMesh mesh;
    auto v = vcg::tri::Allocator<vcg::gaussphere::OrientedPointMesh>::AddVertices(mesh, out.surfels.size());
    std::vector<vcg::Point3f> major, minor;
    std::vector<float> blend;
    for (const SurfelRecord &s : out.surfels) {
        v->P() = P(s.position);
        v->N() = P(s.normal);
        ++v;
        major.push_back(P(s.majorAxis));
        minor.push_back(P(s.minorAxis));
        blend.push_back(s.blendScale);
    }
    vcg::gaussphere::metric::SurfelErrorAttributes attributes;
    attributes.ellipseMajorAxes = &major;
    attributes.ellipseMinorAxes = &minor;
    attributes.blendScale = &blend;
    return vcg::gaussphere::metric::ComputeSurfelError(input, mesh, vcg::gaussphere::metric::SurfelErrorParams(),
                                                        attributes);
}

double Percentile(std::vector<double> values, double fraction)
{
    if (values.empty()) return std::nan("");
    const std::size_t rank = std::min(values.size() - 1, std::size_t(fraction * values.size()));
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(rank), values.end());
    return values[rank];
}

std::vector<Point> Centres(const Output &out)
{
    std::vector<Point> centres;
    for (const SurfelRecord &s : out.surfels) centres.push_back(s.position);
    return centres;
}

void PrintNearestSpacing(const char *name, const Output &out)
{
    const std::vector<Point> centres = Centres(out);
    const PointCloud cloud{centres};
    PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    std::vector<double> inside, across;
    for (std::size_t i = 0; i < centres.size(); ++i) {
        unsigned index[2];
        float squared[2];
        tree.knnSearch(centres[i].data(), 2, index, squared);
        const unsigned other = index[0] == i ? index[1] : index[0];
        (out.tile[other] == out.tile[i] ? inside : across).push_back(std::sqrt(double(squared[1])));
    }
    std::printf("%s_nn_inside_median=%.6g\n%s_nn_across_median=%.6g\n%s_nn_inside_p05=%.6g\n%s_nn_across_p05=%.6g\n"
                "%s_nn_across_count=%zu\n",
                name, Percentile(inside, 0.5), name, Percentile(across, 0.5), name, Percentile(inside, 0.05), name,
                Percentile(across, 0.05), name, across.size());
}

/// Distance from `p` to the nearest face its core box shares with another tile.
double DistanceToInnerFace(const TileGrid &grid, const float p[3])
{
    const GridCell c = grid.CellOf(p);
    double nearest = INFINITY;
    for (int a = 0; a < 3; ++a) {
        const double low = grid.origin[a] + c[a] * grid.edge;
        if (c[a] > 0) nearest = std::min(nearest, double(p[a]) - low);
        if (c[a] + 1 < grid.dims[a]) nearest = std::min(nearest, low + grid.edge - double(p[a]));
    }
    return nearest;
}

void PrintBorderHoles(const char *name, const Output &out, const vcg::gaussphere::OrientedPointMesh &input,
                      const Manifest &manifest, double band)
{
    const std::vector<Point> centres = Centres(out);
    const PointCloud cloud{centres};
    PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    std::size_t border = 0, holes = 0;
    for (const auto &v : input.vert) {
        const float p[3] = {v.cP()[0], v.cP()[1], v.cP()[2]};
        if (DistanceToInnerFace(manifest.grid, p) > band * manifest.spacing) continue;
        ++border;
        unsigned index[16];
        float squared[16];
        const std::size_t found = tree.knnSearch(p, 16, index, squared);
        bool covered = false;
        for (std::size_t k = 0; k < found && !covered; ++k) covered = EllipseCovers(out.surfels[index[k]], p);
        holes += !covered;
    }
    std::printf("%s_border_points=%zu\n%s_border_uncovered=%zu\n", name, border, name, holes);
}

Output ReadWhole(const std::string &path, const Manifest &manifest)
{
    Output out;
    std::string error;
    Require(surfel_io::readSurfelFile(path, out.surfels, error), error);
    for (const SurfelRecord &s : out.surfels) out.tile.push_back(manifest.grid.IdOf(manifest.grid.CellOf(s.position.data())));
    return out;
}

Output ReadTiles(const std::string &dir, const Manifest &manifest)
{
    Output out;
    Rescues rescues;
    std::string error;
    Require(FindRescues(dir, manifest, rescues, error), error);
    std::printf("tiled_rescued_surfels=%llu\ntiled_orphan_points=%llu\ntiled_orphans_uncovered=%llu\n",
                (unsigned long long)rescues.surfels, (unsigned long long)rescues.orphans,
                (unsigned long long)rescues.uncovered);
    for (std::size_t t = 0; t < manifest.tiles.size(); ++t) {
        std::vector<SurfelRecord> records;
        Require(ReadTileOutput(dir, manifest.tiles[t].id, rescues.spares[t], records, error), error);
        out.surfels.insert(out.surfels.end(), records.begin(), records.end());
        out.tile.insert(out.tile.end(), records.size(), manifest.tiles[t].id);
    }
    return out;
}

void PrintFigure(const char *name, double whole, double tiled)
{
    std::printf("%s_whole=%.10g\n%s_tiled=%.10g\n%s_diff_pct=%.3f\n", name, whole, name, tiled, name,
                100.0 * (tiled - whole) / whole);
}

double Members(const Output &out)
{
    double sum = 0;
    for (const SurfelRecord &s : out.surfels) sum += s.quality;
    return sum;
}

} // namespace

int main(int argc, char **argv)
{
    Require(argc == 4 || argc == 5, "usage: gstile_compare TILEDIR WHOLE.surfel TILED.surfel [BAND]");
    const std::string dir = argv[1];
    const double band = argc == 5 ? std::atof(argv[4]) : 3.0;
    Manifest manifest;
    std::string error;
    Require(ReadManifest(dir, manifest, error), error);
    vcg::gaussphere::OrientedPointMesh input;
    Require(gsresample::ReadOrientedPoints(manifest.input, input, error), error);
    const Output whole = ReadWhole(argv[2], manifest);
    Output tiled = ReadTiles(dir, manifest);
    std::vector<SurfelRecord> merged;
    Require(surfel_io::readSurfelFile(argv[3], merged, error), error);
    Require(merged == tiled.surfels, std::string(argv[3]) + " is not the tiles' results in tile order");
    PrintFigure("count", double(whole.surfels.size()), double(tiled.surfels.size()));
    PrintFigure("members", Members(whole), Members(tiled));
    const auto mw = Metric(input, whole), mt = Metric(input, tiled);
    PrintFigure("delta_rms", mw.normalizedDistance.rms, mt.normalizedDistance.rms);
    PrintFigure("delta_max", mw.normalizedDistance.max, mt.normalizedDistance.max);
    PrintFigure("delta_p999", mw.normalizedDistance.p999, mt.normalizedDistance.p999);
    PrintFigure("l21_own_rms", mw.normalToOwnSurfel.rms, mt.normalToOwnSurfel.rms);
    PrintFigure("l21_own_max", mw.normalToOwnSurfel.max, mt.normalToOwnSurfel.max);
    PrintFigure("l21_own_p999", mw.normalToOwnSurfel.p999, mt.normalToOwnSurfel.p999);
    PrintFigure("l21_blended_rms", mw.normalToBlended.rms, mt.normalToBlended.rms);
    PrintFigure("l21_blended_max", mw.normalToBlended.max, mt.normalToBlended.max);
    PrintFigure("l21_blended_p999", mw.normalToBlended.p999, mt.normalToBlended.p999);
    PrintNearestSpacing("whole", whole);
    PrintNearestSpacing("tiled", tiled);
    PrintBorderHoles("whole", whole, input, manifest, band);
    PrintBorderHoles("tiled", tiled, input, manifest, band);
    return 0;
}
