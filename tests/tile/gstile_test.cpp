// gstile's parts (tools/gstile): the grid's ownership of points, the ownership of clusters, the
// sharing of a target, a split-run-merge of the bunny against its whole run (at the level and
// with a target), and what a damaged tile directory gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <random>
#include <set>

#include <io_surfel/surfel_file.h>
#include <io_surfel/surfel_records_mesh.h>
#include <tools/gsresample/ply_input.h>
#include <vcg_ext/gaussphere/surfels/surfel_mesh.h>
#include <tools/gstile/border_points.h>
#include <tools/gstile/merge.h>
#include <tools/gstile/split.h>
#include <tools/gstile/target_share.h>
#include <tools/gstile/tile_params.h>
#include <tools/gstile/tile_run.h>
#include <vcg_ext/surfel/percentile.h>

using namespace gstile;

namespace {

const std::string kBunny = std::string(GAUSSPHERE_TEST_DATA_DIR) + "/bunny.ply";

TEST(TileGrid, EveryPointHasOneCoreAndItsHaloTilesReachIt)
{
    TileGrid grid;
    grid.origin = {{-1, -2, 0}};
    grid.edge = 0.5;
    grid.dims = {{4, 8, 2}};
    std::mt19937 random(3);
    std::uniform_real_distribution<float> x(-1, 1), y(-2, 2), z(0, 1);
    const double halo = 0.2;
    for (int i = 0; i < 20000; ++i) {
        // Every tenth point on a grid plane or on the box's far faces.
        float p[3] = {x(random), y(random), z(random)};
        if (i % 10 == 0) p[i % 3] = i % 20 == 0 ? float(grid.origin[i % 3] + grid.edge * (i % 4)) : 1.0f;
        const GridCell home = grid.CellOf(p);
        for (int a = 0; a < 3; ++a) {
            ASSERT_GE(home[a], 0);
            ASSERT_LT(home[a], grid.dims[a]);
            const double low = grid.origin[a] + grid.edge * home[a];
            ASSERT_TRUE(p[a] >= low && (p[a] < low + grid.edge || home[a] == grid.dims[a] - 1)) << "half-open core";
        }
        std::set<int> halos;
        grid.ForHaloTiles(p, halo, home, [&](int id) { halos.insert(id); });
        EXPECT_EQ(halos.count(grid.IdOf(home)), 0u);
        for (int id = 0; id < grid.TileCount(); ++id) {
            const GridCell c = grid.CellOfId(id);
            bool near = true;
            for (int a = 0; a < 3; ++a) {
                const double low = grid.origin[a] + grid.edge * c[a];
                near = near && p[a] >= low - halo && p[a] <= low + grid.edge + halo;
            }
            if (id != grid.IdOf(home)) ASSERT_EQ(near, halos.count(id) == 1) << "tile " << id;
        }
    }
}

TEST(Ownership, TheTileOfTheSmallestInputIndexKeepsTheCluster)
{
    vcg::gaussphere::ResamplingResult result;
    result.surfels.resize(4);
    // Vertices 0-2 are the core, 3-5 the halo; input indices are not in vertex order.
    const std::vector<std::uint64_t> indices = {40, 12, 7, 3, 50, 9};
    result.representative = {0, 0, 1, 1, 2, 3};
    // Surfel 0: {40, 12} both core. 1: {7 core, 3 halo}: anchor 3, another tile's. 2: {50} halo.
    // 3: {9} halo.
    const std::vector<bool> owned = OwnedSurfels(result, indices, 3);
    EXPECT_EQ(owned, (std::vector<bool>{true, false, false, false}));
}

/// SpreadEvenly grows clusters across the whole input: a split refuses it with a reason, and a
/// manifest written without it carries no such option.
TEST(TileOptions, SpreadEvenlyIsRefusedWithTheReason)
{
    gstile::Manifest manifest;
    manifest.points = 1000;
    manifest.diagonal = 1;
    vcg::gaussphere::ResamplingParams param;
    param.spreadEvenly = true;
    std::string error;
    EXPECT_FALSE(gstile::SetTileOptions(param, manifest, error));
    EXPECT_NE(error.find("--spread-evenly"), std::string::npos) << error;
    param.spreadEvenly = false;
    EXPECT_TRUE(gstile::SetTileOptions(param, manifest, error)) << error;
}

TEST(BorderPoints, ATileRecordsTheHaloPointsItTakesAndTheCorePointsItLeaves)
{
    vcg::gaussphere::ResamplingResult result;
    result.surfels.resize(4);
    // As in Ownership above: surfel 0 kept, 1 left (core 7 with halo 3), 2 and 3 left (halo only).
    const std::vector<std::uint64_t> indices = {40, 12, 7, 3, 50, 9};
    vcg::gaussphere::OrientedPointMesh points;
    auto v = vcg::tri::Allocator<vcg::gaussphere::OrientedPointMesh>::AddVertices(points, 6);
    for (int i = 0; i < 6; ++i, ++v) v->P() = vcg::Point3f(float(i), 0, 0);
    result.representative = {0, 0, 1, 1, 2, 3};
    std::vector<bool> owned = {true, false, false, false};
    std::vector<int> spares;
    TileBorder border = BorderOf(result, indices, points, 3, owned, spares);
    EXPECT_TRUE(border.takenOver.empty()) << "no kept surfel holds a halo point";
    ASSERT_EQ(spares, std::vector<int>{1}) << "only surfel 1 holds a core point among those left";
    ASSERT_EQ(border.leftPoints.size(), 1u);
    ASSERT_EQ(border.leftPoints[0].size(), 1u);
    EXPECT_EQ(border.leftPoints[0][0].index, 7u);
    EXPECT_EQ(border.leftPoints[0][0].position[0], 2.0f);
    // Surfel 2 kept instead: it takes over halo point 50.
    owned = {true, false, true, false};
    border = BorderOf(result, indices, points, 3, owned, spares);
    EXPECT_EQ(border.takenOver, std::vector<std::uint64_t>{50});

    const std::string dir = ::testing::TempDir() + "gstile_border_record";
    ASSERT_EQ(std::system(("mkdir -p " + dir).c_str()), 0);
    border.leftPoints.push_back({LeftPoint(), LeftPoint()});
    std::string error;
    ASSERT_TRUE(WriteBorder(dir, 5, border, error)) << error;
    TileBorder read;
    ASSERT_TRUE(ReadBorder(dir, 5, read, error)) << error;
    EXPECT_EQ(read.takenOver, border.takenOver);
    ASSERT_EQ(read.leftPoints.size(), 2u);
    EXPECT_EQ(read.leftPoints[0][0].index, 7u);
    EXPECT_EQ(read.leftPoints[1].size(), 2u);
    // Cut short: refused, the tile named.
    std::ifstream in(TilePath(dir, 5, ".border"), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(TilePath(dir, 5, ".border"), std::ios::binary) << bytes.substr(0, bytes.size() - 4);
    EXPECT_FALSE(ReadBorder(dir, 5, read, error));
    EXPECT_NE(error.find("tile 5:"), std::string::npos) << error;
    // A position that is no number (it would hide every point from the cover check): refused.
    border.leftPoints[1][0].position[1] = std::nanf("");
    ASSERT_TRUE(WriteBorder(dir, 5, border, error)) << error;
    EXPECT_FALSE(ReadBorder(dir, 5, read, error));
    EXPECT_NE(error.find("damaged"), std::string::npos) << error;
}

TEST(BorderPoints, AnEllipseCoversWhatLiesInsideItAndNearItsPlane)
{
    surfel_io::SurfelRecord s{};
    s.position = {{10, 20, 30}};
    s.normal = {{0, 0, 1}};
    s.majorAxis = {{2, 0, 0}};
    s.minorAxis = {{0, 1, 0}};
    const float inside[3] = {11.5f, 20.5f, 31.9f}, outside[3] = {11.5f, 20.8f, 30}, above[3] = {10, 20, 32.1f};
    EXPECT_TRUE(EllipseCovers(s, inside));
    EXPECT_FALSE(EllipseCovers(s, outside)) << "(1.5/2)^2 + 0.8^2 > 1";
    EXPECT_FALSE(EllipseCovers(s, above)) << "farther off the plane than the major semi-axis";
}

/// The bunny split into small tiles in a fresh directory.
class BunnyTiles : public ::testing::Test
{
protected:
    void SetUp() override
    {
        dir_ = ::testing::TempDir() + "gstile_bunny_" + ::testing::UnitTest::GetInstance()->current_test_info()->name();
        SplitOptions options;
        options.tilePoints = 20000;
        std::string error;
        ASSERT_TRUE(Split(kBunny, dir_, options, manifest_, [](const std::string &) {}, error)) << error;
        ASSERT_GE(manifest_.tiles.size(), 4u);
    }
    void RunAll()
    {
        for (const TileEntry &t : manifest_.tiles) {
            TileRunFigures figures;
            std::string error;
            ASSERT_TRUE(RunTile(dir_, manifest_, t.id, figures, error)) << error;
        }
    }
    std::string dir_;
    Manifest manifest_;
};

TEST_F(BunnyTiles, TiledCountAndRepresentedPointsMatchTheWholeRun)
{
    vcg::gaussphere::OrientedPointMesh mesh;
    std::string error;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(kBunny, mesh, error)) << error;
    const auto whole = vcg::gaussphere::ResamplePointSet(mesh, vcg::gaussphere::ResamplingParams());
    RunAll();
    MergeFigures figures;
    ASSERT_TRUE(Merge(dir_, manifest_, dir_ + "/merged.surfel", figures, error)) << error;
    EXPECT_NEAR(double(figures.surfels), double(whole.surfels.size()), 0.005 * whole.surfels.size());
    // Each input point belongs to one kept cluster, up to the few border clusters the tiles
    // cut differently.
    EXPECT_NEAR(double(figures.members), double(manifest_.points), 0.005 * manifest_.points);
    std::uint64_t core = 0;
    for (const TileEntry &t : manifest_.tiles) core += t.corePoints;
    EXPECT_EQ(core, manifest_.points) << "every point in exactly one core";
}

TEST_F(BunnyTiles, TheMergeKeepsASurfelForEveryBorderPointNoTileKeepsNorCovers)
{
    // Halos of half a sample spacing: the tiles cut many border clusters differently.
    SplitOptions options;
    options.tilePoints = 20000;
    options.haloSpacings = 0.5;
    std::string error;
    dir_ += "_narrow";
    ASSERT_TRUE(Split(kBunny, dir_, options, manifest_, [](const std::string &) {}, error)) << error;
    RunAll();
    Rescues rescues;
    ASSERT_TRUE(FindRescues(dir_, manifest_, rescues, error)) << error;
    EXPECT_GT(rescues.uncovered, 0u);
    EXPECT_LT(2 * rescues.uncovered, rescues.orphans) << "most orphans lie under a neighbour's ellipse";
    EXPECT_GT(rescues.surfels, 0u);
    EXPECT_LE(rescues.surfels, rescues.uncovered);
    MergeFigures figures;
    ASSERT_TRUE(Merge(dir_, manifest_, dir_ + "/merged.surfel", figures, error)) << error;
    std::vector<surfel_io::SurfelRecord> merged, results;
    ASSERT_TRUE(surfel_io::readSurfelFile(dir_ + "/merged.surfel", merged, error)) << error;
    for (const TileEntry &t : manifest_.tiles) {
        std::vector<surfel_io::SurfelRecord> records;
        ASSERT_TRUE(surfel_io::readSurfelFile(TilePath(dir_, t.id, ".surfel"), records, error)) << error;
        results.insert(results.end(), records.begin(), records.end());
    }
    EXPECT_EQ(merged.size(), results.size() + rescues.surfels);
    // Judged on the input alone: the input points no ellipse covers, in the tiles' results and in the
    // merged output, against the whole run's.
    vcg::gaussphere::OrientedPointMesh input;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(kBunny, input, error)) << error;
    const auto uncovered = [&input](const std::vector<surfel_io::SurfelRecord> &surfels) {
        std::size_t count = 0;
        for (const auto &v : input.vert) {
            const float p[3] = {v.cP()[0], v.cP()[1], v.cP()[2]};
            count += std::none_of(surfels.begin(), surfels.end(),
                                  [&p](const surfel_io::SurfelRecord &s) { return EllipseCovers(s, p); });
        }
        return count;
    };
    const auto whole = vcg::gaussphere::ResamplePointSet(input, vcg::gaussphere::ResamplingParams());
    vcg::gaussphere::OrientedPointMesh wholeMesh;
    vcg::gaussphere::WriteSurfels(whole.surfels, wholeMesh);
    const std::size_t inResults = uncovered(results), inMerged = uncovered(merged),
                      inWhole = uncovered(surfel_io::recordsFromMesh(wholeMesh));
    EXPECT_GT(inResults, inWhole) << "narrow halos leave holes along the faces";
    EXPECT_LE(inMerged, inWhole) << "the rescued surfels fill them";

    // A damaged border record stops the merge with its tile named.
    const int id = manifest_.tiles[1].id;
    std::ofstream(TilePath(dir_, id, ".border"), std::ios::binary) << "gsborde1";
    EXPECT_FALSE(Merge(dir_, manifest_, dir_ + "/merged2.surfel", figures, error));
    EXPECT_NE(error.find("tile " + std::to_string(id) + ":"), std::string::npos) << error;
}

/// Writes the bunny moved by `offset` with double x y z and float normals; returns the path.
std::string WriteDoubleBunny(const std::string &path, const std::array<double, 3> &offset)
{
    vcg::gaussphere::OrientedPointMesh bunny;
    std::string error;
    EXPECT_TRUE(gsresample::ReadOrientedPoints(kBunny, bunny, error)) << error;
    std::ofstream out(path, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << bunny.vert.size() << "\n"
        << "property double x\nproperty double y\nproperty double z\n"
        << "property float nx\nproperty float ny\nproperty float nz\nend_header\n";
    for (const auto &v : bunny.vert) {
        for (int a = 0; a < 3; ++a) {
            const double position = double(v.cP()[a]) + offset[size_t(a)];
            out.write(reinterpret_cast<const char *>(&position), sizeof position);
        }
        out.write(reinterpret_cast<const char *>(&v.cN()[0]), 3 * sizeof(float));
    }
    return path;
}

/// Splits, runs and merges `input` into the PLY `output`, tiles in `dir`.
void TileToPly(const std::string &input, const std::string &dir, const std::string &output)
{
    SplitOptions options;
    options.tilePoints = 20000;
    Manifest manifest;
    std::string error;
    ASSERT_TRUE(Split(input, dir, options, manifest, [](const std::string &) {}, error)) << error;
    ASSERT_TRUE(manifest.doubleCoordinates);
    for (const TileEntry &t : manifest.tiles) {
        TileRunFigures figures;
        ASSERT_TRUE(RunTile(dir, manifest, t.id, figures, error)) << error;
    }
    MergeFigures figures;
    ASSERT_TRUE(Merge(dir, manifest, output, figures, error)) << error;
}

/// x y z of each vertex of a merged PLY with double coordinates.
std::vector<std::array<double, 3>> ReadDoublePositions(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    std::string line, header;
    std::size_t count = 0;
    while (std::getline(in, line) && line != "end_header") {
        header += line + "\n";
        if (line.rfind("element vertex ", 0) == 0) count = std::stoul(line.substr(15));
    }
    EXPECT_NE(header.find("property double x\nproperty double y\nproperty double z\nproperty float nx\n"),
              std::string::npos) << header;
    std::vector<std::array<double, 3>> positions(count);
    for (auto &p : positions) {
        in.read(reinterpret_cast<char *>(p.data()), sizeof p);
        in.ignore(5 * sizeof(float)); // nx ny nz radius quality
    }
    EXPECT_TRUE(bool(in));
    return positions;
}

// A georeferenced scan (UTM metres, where floats step by 0.25 m; the bunny is 0.26 m across)
// tiles as the same scan at the origin does: split streams double positions relative to a point
// of the model, and merge moves the surfels back, in double.
TEST(DoubleCoordinates, TileFarFromTheOriginAsNearIt)
{
    const std::string dir = ::testing::TempDir() + "gstile_double_";
    const std::array<double, 3> far{{500000, 4000000, 100}};
    TileToPly(WriteDoubleBunny(dir + "near.ply", {{0, 0, 0}}), dir + "near.tiles", dir + "near_out.ply");
    TileToPly(WriteDoubleBunny(dir + "far.ply", far), dir + "far.tiles", dir + "far_out.ply");
    const auto near = ReadDoublePositions(dir + "near_out.ply"), moved = ReadDoublePositions(dir + "far_out.ply");
    ASSERT_GT(near.size(), 5000u);
    ASSERT_EQ(moved.size(), near.size());
    for (std::size_t i = 0; i < near.size(); ++i)
        for (int a = 0; a < 3; ++a)
            ASSERT_NEAR(moved[i][size_t(a)] - far[size_t(a)], near[i][size_t(a)], 1e-8) << "surfel " << i;
}

TEST_F(BunnyTiles, ACorruptOrTruncatedTileFileIsRefusedWithTheTileNamed)
{
    const TileEntry &tile = manifest_.tiles[1];
    const std::string core = TilePath(dir_, tile.id, ".core");
    {
        std::fstream f(core, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(100);
        f.put('\x7f');
    }
    TileRunFigures figures;
    std::string error;
    EXPECT_FALSE(RunTile(dir_, manifest_, tile.id, figures, error));
    EXPECT_NE(error.find("tile " + std::to_string(tile.id) + ":"), std::string::npos) << error;
    EXPECT_NE(error.find("corrupt"), std::string::npos) << error;
    std::ofstream(core, std::ios::binary | std::ios::app) << "extra";
    EXPECT_FALSE(RunTile(dir_, manifest_, tile.id, figures, error));
    EXPECT_NE(error.find("bytes"), std::string::npos) << error;
}

TEST_F(BunnyTiles, AMissingOrPartialResultStopsTheMergeWithTheTileNamed)
{
    RunAll();
    const TileEntry &tile = manifest_.tiles[2];
    const std::string result = TilePath(dir_, tile.id, ".surfel");
    // A run killed while writing leaves only its temporary file: the result is missing.
    ASSERT_EQ(std::rename(result.c_str(), (result + ".tmp4242").c_str()), 0);
    MergeFigures figures;
    std::string error;
    EXPECT_FALSE(Merge(dir_, manifest_, dir_ + "/merged.surfel", figures, error));
    EXPECT_NE(error.find("tile " + std::to_string(tile.id) + ":"), std::string::npos) << error;
    // A result cut short (written by something else than gstile run) is refused too.
    std::ifstream in(result + ".tmp4242", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(result, std::ios::binary) << bytes.substr(0, bytes.size() - 10);
    EXPECT_FALSE(Merge(dir_, manifest_, dir_ + "/merged.surfel", figures, error));
    EXPECT_NE(error.find("tile " + std::to_string(tile.id) + ":"), std::string::npos) << error;
    std::ifstream merged(dir_ + "/merged.surfel");
    EXPECT_FALSE(merged.good()) << "no output from a failed merge";
}

TEST_F(BunnyTiles, ARerunGivesTheSameBytes)
{
    RunAll();
    const std::string result = TilePath(dir_, manifest_.tiles[0].id, ".surfel");
    std::ifstream first(result, std::ios::binary);
    const std::string before((std::istreambuf_iterator<char>(first)), std::istreambuf_iterator<char>());
    TileRunFigures figures;
    std::string error;
    ASSERT_TRUE(RunTile(dir_, manifest_, manifest_.tiles[0].id, figures, error)) << error;
    std::ifstream second(result, std::ios::binary);
    const std::string after((std::istreambuf_iterator<char>(second)), std::istreambuf_iterator<char>());
    EXPECT_EQ(before, after);
}

/// Two tiles of 1,000 points, each making twice the clusters it owns at every level.
Manifest TwoTiles(std::uint64_t target)
{
    Manifest manifest;
    manifest.targetCount = target;
    manifest.tiles.resize(2);
    for (int t = 0; t < 2; ++t) {
        manifest.tiles[t].id = 5 + t;
        manifest.tiles[t].corePoints = manifest.tiles[t].haloPoints = 500;
    }
    return manifest;
}

void ProbeLevel(TileProbe &probe, int level, std::uint64_t owned) { probe.levels.push_back({level, 2 * owned, owned}); }

TEST(TargetShare, TheProbesFollowTheLevelSearchOfTheTilesSummedCounts)
{
    const Manifest manifest = TwoTiles(100);
    std::vector<TileProbe> probes(2);
    ShareDecision d = DecideShares(manifest, 8, 1.15, probes);
    ASSERT_FALSE(d.shared);
    ASSERT_EQ(d.needs.size(), 2u);
    EXPECT_EQ(d.needs[0].level, 8) << "the search starts at the level asked for";
    EXPECT_EQ(d.needs[0].recordCap, 0u);
    ProbeLevel(probes[0], 8, 150);
    d = DecideShares(manifest, 8, 1.15, probes);
    EXPECT_EQ(d.needs[1].level, 8) << "until every tile has it";
    EXPECT_TRUE(Satisfies(probes[0], d.needs[0]));
    ProbeLevel(probes[1], 8, 50); // 200 > 100: coarser
    d = DecideShares(manifest, 8, 1.15, probes);
    EXPECT_EQ(d.needs[0].level, 4);
    ProbeLevel(probes[0], 4, 60);
    ProbeLevel(probes[1], 4, 20); // 80 fits: between 4 and 8
    d = DecideShares(manifest, 8, 1.15, probes);
    EXPECT_EQ(d.needs[0].level, 6);
    ProbeLevel(probes[0], 6, 90);
    ProbeLevel(probes[1], 6, 30); // 120 > 100
    ProbeLevel(probes[0], 5, 70);
    ProbeLevel(probes[1], 5, 25); // 95 fits; 6 gives 1.2 x the target, beyond 1.15: split level 5
    d = DecideShares(manifest, 8, 1.15, probes);
    ASSERT_FALSE(d.shared);
    EXPECT_EQ(d.needs[0].level, 5);
    EXPECT_EQ(d.needs[0].recordCap, kMinRecordCap) << "a few missing: the fewest a tile records";
    const Manifest many = TwoTiles(2000);
    ProbeLevel(probes[0], 16, 1200);
    ProbeLevel(probes[1], 16, 400);
    ProbeLevel(probes[0], 32, 3000);
    ProbeLevel(probes[1], 32, 1000);
    ProbeLevel(probes[0], 24, 2000);
    ProbeLevel(probes[1], 24, 600);
    ProbeLevel(probes[0], 20, 1600);
    ProbeLevel(probes[1], 20, 500);
    ProbeLevel(probes[0], 18, 1600);
    ProbeLevel(probes[1], 18, 500);
    ProbeLevel(probes[0], 17, 1500);
    ProbeLevel(probes[1], 17, 520); // 2,020: only level 16 fits, with 1,600: 400 missing, owned 3 : 1
    d = DecideShares(many, 16, 1.0, probes);
    ASSERT_FALSE(d.shared);
    EXPECT_EQ(d.needs[0].level, 16);
    EXPECT_EQ(d.needs[0].recordCap, 1200u) << "twice its 300 of the 400 missing, times 2 made per owned";
    EXPECT_EQ(d.needs[1].recordCap, 400u) << "twice its 100, times 2";

    // At 1.25 the level giving 120 is merged down instead: 20 in excess, owned 90 : 30.
    d = DecideShares(manifest, 8, 1.25, probes);
    ASSERT_FALSE(d.shared);
    EXPECT_EQ(d.needs[0].level, 6);
    EXPECT_TRUE(d.needs[0].merges);
    EXPECT_EQ(d.needs[0].recordCap, kMinRecordCap) << "twice its 15 of the 20, times 2: fewer than the fewest";
}

TEST(TargetShare, MergesAreTakenInCostOrderAcrossTheTiles)
{
    const Manifest manifest = TwoTiles(10);
    std::vector<TileProbe> probes(2);
    for (int t = 0; t < 2; ++t) {
        ProbeLevel(probes[t], 2, 7); // level 2 gives 14, 1.4 times the target: merged down
        probes[t].recordLevel = 2;
        probes[t].recordCap = kMinRecordCap;
    }
    // The four owned merges in excess go 3 : 1 by cost; tile 6's halo merge at 0.3 runs too.
    probes[0].merges = {{0.1, true}, {0.2, true}, {0.4, false}, {0.5, true}, {0.9, true}};
    probes[1].merges = {{0.3, false}, {0.45, true}, {0.6, true}};
    const ShareDecision d = DecideShares(manifest, 2, 1.15, probes);
    ASSERT_TRUE(d.shared);
    EXPECT_EQ(d.shares.level, 2);
    EXPECT_EQ(d.shares.tiles[0].owned, 7u - 3u);
    EXPECT_EQ(d.shares.tiles[1].owned, 7u - 1u);
    EXPECT_EQ(d.shares.tiles[0].target, 14u - 4u) << "0.1, 0.2, 0.4 (halo) and 0.5";
    EXPECT_EQ(d.shares.tiles[1].target, 14u - 2u) << "0.3 (halo) and 0.45";

    // A record cut short by its cap and taken whole may hide merges below the threshold.
    std::vector<TileProbe> cut = probes;
    cut[0].merges.clear();
    for (std::uint64_t k = 0; k < kMinRecordCap; ++k) cut[0].merges.push_back({0.01 * double(k), false});
    cut[1].merges = {{5.0, true}, {6.0, true}, {7.0, true}, {8.0, true}};
    const ShareDecision more = DecideShares(manifest, 2, 1.15, cut);
    ASSERT_FALSE(more.shared);
    EXPECT_EQ(more.needs[0].recordCap, 2 * kMinRecordCap);
    EXPECT_TRUE(more.needs[0].merges);
    EXPECT_TRUE(Satisfies(cut[1], more.needs[1])) << "a record shorter than its cap holds all the tile's merges";
}

TEST(TargetShare, SplitsAreTakenInPriorityOrderAcrossTheTiles)
{
    const Manifest manifest = TwoTiles(10);
    std::vector<TileProbe> probes(2);
    for (int t = 0; t < 2; ++t) {
        ProbeLevel(probes[t], 2, 3); // level 2 fits (6 of 10), levels 3 and 4 give far too many
        ProbeLevel(probes[t], 4, 30);
        ProbeLevel(probes[t], 3, 20);
        probes[t].recordLevel = 2;
        probes[t].recordCap = kMinRecordCap;
    }
    // Tile 5's priorities fall fast, tile 6's slowly: the four owned splits missing go 1 : 3.
    probes[0].splits = {{9.0, 10, true}, {4.0, 6, false}, {1.0, 4, true}, {0.5, 3, true}};
    probes[1].splits = {{8.0, 12, true}, {7.0, 9, true}, {6.0, 8, false}, {5.0, 7, true}, {4.0, 6, true}};
    const ShareDecision d = DecideShares(manifest, 2, 1.15, probes);
    ASSERT_TRUE(d.shared);
    EXPECT_EQ(d.shares.level, 2);
    EXPECT_EQ(d.shares.tiles[0].owned, 4u) << "3 at the level and the split at 9.0";
    EXPECT_EQ(d.shares.tiles[1].owned, 6u) << "3 and the owned ones of 8.0, 7.0, 5.0";
    EXPECT_EQ(d.shares.tiles[0].target, 6u + 1u);
    EXPECT_EQ(d.shares.tiles[1].target, 6u + 4u) << "the halo's split at 6.0 runs too";

    // A record cut short by its cap and taken whole (its splits add halo clusters only): it may
    // hide splits above the threshold, so that tile records twice as many.
    std::vector<TileProbe> cut = probes;
    cut[0].splits.clear();
    for (std::uint64_t k = 0; k < kMinRecordCap; ++k) cut[0].splits.push_back({9.0 - 0.01 * double(k), 9, false});
    cut[1].splits = {{1.0, 2, true}};
    const ShareDecision more = DecideShares(manifest, 2, 1.15, cut);
    ASSERT_FALSE(more.shared);
    EXPECT_EQ(more.needs[0].recordCap, 2 * kMinRecordCap);
    EXPECT_FALSE(Satisfies(cut[0], more.needs[0]));
    EXPECT_TRUE(Satisfies(cut[1], more.needs[1])) << "a record shorter than its cap holds all the tile's splits";
}

// A probe file is read back exactly, and one damaged (cut short, its step records of unequal
// length, rising splits or falling merges, more merges than its level allows, counts out of
// range) is refused with the file named.
TEST(TargetShare, AProbeFileIsReadBackOrRefusedWithTheFileNamed)
{
    const std::string dir = ::testing::TempDir() + "gstile_probe_file";
    ASSERT_EQ(std::system(("mkdir -p " + dir).c_str()), 0);
    TileProbe probe;
    probe.id = 3;
    probe.levels = {{8, 120, 70}, {4, 40, 25}};
    probe.recordLevel = 4;
    probe.recordCap = 6;
    probe.splits = {{0.75, 9, true}, {0.5, 7, false}, {0.5, 5, true}};
    std::string error;
    ASSERT_TRUE(WriteProbe(dir, probe, error)) << error;
    TileProbe back;
    ASSERT_TRUE(ReadProbe(dir, 3, back, error)) << error;
    ASSERT_EQ(back.levels.size(), 2u);
    EXPECT_EQ(back.At(4)->owned, 25u);
    EXPECT_EQ(back.At(6), nullptr);
    ASSERT_EQ(back.splits.size(), 3u);
    EXPECT_EQ(back.splits[2].size, 5);
    EXPECT_TRUE(back.splits[2].addsOwned);
    EXPECT_FALSE(ReadProbe(dir, 4, back, error)) << "no probe yet";
    EXPECT_TRUE(error.empty()) << "is not an error";
    probe.splits.clear();
    probe.merges = {{0.25, false}, {0.5, true}, {0.5, true}};
    ASSERT_TRUE(WriteProbe(dir, probe, error)) << error;
    ASSERT_TRUE(ReadProbe(dir, 3, back, error)) << error;
    ASSERT_EQ(back.merges.size(), 3u);
    EXPECT_TRUE(back.splits.empty());
    EXPECT_EQ(back.merges[0].cost, 0.25);
    EXPECT_FALSE(back.merges[0].removesOwned);
    EXPECT_TRUE(back.merges[2].removesOwned);
    EXPECT_TRUE(Satisfies(back, {4, 6, true}));
    EXPECT_FALSE(Satisfies(back, {4, 6, false})) << "merges do not answer a need for splits";

    const std::string path = TilePath(dir, 3, ".probe");
    const auto refused = [&](const std::string &text, const char *why) {
        std::ofstream(path, std::ios::trunc) << text;
        std::string reason;
        EXPECT_FALSE(ReadProbe(dir, 3, back, reason)) << why;
        EXPECT_NE(reason.find(path), std::string::npos) << why << ": " << reason;
    };
    refused("{\"levels\": [[8, 120", "cut short");
    refused("{\"levels\": [], \"record_level\": 4, \"record_cap\": 6, \"split_error\": [0.5, 0.4], "
            "\"split_size\": [3], \"split_adds_owned\": [1, 0], \"merge_cost\": [], \"merge_removes_owned\": []}", "lengths differ");
    refused("{\"levels\": [], \"record_level\": 4, \"record_cap\": 6, \"split_error\": [0.5, 0.9], "
            "\"split_size\": [3, 3], \"split_adds_owned\": [1, 0], \"merge_cost\": [], \"merge_removes_owned\": []}", "a priority rises");
    refused("{\"levels\": [], \"record_level\": 4, \"record_cap\": 1, \"split_error\": [0.5, 0.4], "
            "\"split_size\": [3, 3], \"split_adds_owned\": [1, 0], \"merge_cost\": [], \"merge_removes_owned\": []}", "more splits than the cap");
    refused("{\"levels\": [], \"record_level\": 4, \"record_cap\": 6, \"split_error\": [0.5, 0.5], "
            "\"split_size\": [3, 4], \"split_adds_owned\": [1, 0], \"merge_cost\": [], \"merge_removes_owned\": []}", "a size rises at an equal error");
    refused("{\"levels\": [], \"record_level\": 4, \"record_cap\": 6, \"split_error\": [1e999], "
            "\"split_size\": [3], \"split_adds_owned\": [1], \"merge_cost\": [], \"merge_removes_owned\": []}", "a number beyond double");
    refused("{\"levels\": [[8, 10, 12]], \"record_level\": 0, \"record_cap\": 0, \"split_error\": [], "
            "\"split_size\": [], \"split_adds_owned\": [], \"merge_cost\": [], \"merge_removes_owned\": []}", "more owned than made");
    refused("{\"levels\": [[300, 10, 5]], \"record_level\": 0, \"record_cap\": 0, \"split_error\": [], "
            "\"split_size\": [], \"split_adds_owned\": [], \"merge_cost\": [], \"merge_removes_owned\": []}", "a level beyond 256");
    refused("{\"levels\": [], \"record_level\": 4, \"record_cap\": 18446744073709551615, \"split_error\": [], "
            "\"split_size\": [], \"split_adds_owned\": [], \"merge_cost\": [], \"merge_removes_owned\": []}", "a cap that would overflow when doubled");
    refused("{\"levels\": [], \"record_level\": 4, \"record_cap\": 6, \"split_error\": [], \"split_size\": [], "
            "\"split_adds_owned\": [], \"merge_cost\": [0.5, 0.4], \"merge_removes_owned\": [1, 0]}", "a merge cost falls");
    refused("{\"levels\": [], \"record_level\": 4, \"record_cap\": 6, \"split_error\": [], \"split_size\": [], "
            "\"split_adds_owned\": [], \"merge_cost\": [0.5], \"merge_removes_owned\": [1, 0]}", "merge lengths differ");
    refused("{\"levels\": [], \"record_level\": 4, \"record_cap\": 6, \"split_error\": [0.5], \"split_size\": [3], "
            "\"split_adds_owned\": [1], \"merge_cost\": [0.5], \"merge_removes_owned\": [1]}", "splits and merges");
    refused("{\"levels\": [[4, 3, 1]], \"record_level\": 4, \"record_cap\": 6, \"split_error\": [], \"split_size\": [], "
            "\"split_adds_owned\": [], \"merge_cost\": [0.1, 0.2, 0.3], \"merge_removes_owned\": [0, 0, 0]}",
            "as many merges as the level has clusters");
    refused("{\"levels\": [[4, 9, 1]], \"record_level\": 4, \"record_cap\": 6, \"split_error\": [], \"split_size\": [], "
            "\"split_adds_owned\": [], \"merge_cost\": [0.1, 0.2], \"merge_removes_owned\": [1, 1]}",
            "more owned clusters taken away than owned");
    refused("{\"levels\": [], \"record_level\": 4, \"record_cap\": 6, \"split_error\": [], \"split_size\": [], "
            "\"split_adds_owned\": [], \"merge_cost\": [0.1], \"merge_removes_owned\": [0]}", "merges at a level not counted");
    refused("{\"levels\": [[4, 90, 10]], \"record_level\": 4, \"record_cap\": 1, \"split_error\": [], \"split_size\": [], "
            "\"split_adds_owned\": [], \"merge_cost\": [0.1, 0.2], \"merge_removes_owned\": [0, 0]}", "more merges than the cap");
    refused("{\"levels\": [[4, 90, 10]], \"record_level\": 4, \"record_cap\": 6, \"split_error\": [], \"split_size\": [], "
            "\"split_adds_owned\": [], \"merge_cost\": 0.1, \"merge_removes_owned\": [0]}", "merges not an array");
}

// The whole run makes each exchange at its worst point: the round goes to the tile whose largest
// distance is highest after the rounds it has, and the rounds end where that tile kept no more.
TEST(TargetShare, EachRoundOfExchangesGoesToTheTileOfTheWorstPoint)
{
    const std::vector<std::vector<double>> maxima = {{5, 4, 3}, {4.5, 1}, {}, {2, 1.5, 1.2, 1}};
    EXPECT_EQ(ShareExchangeRounds(maxima, 16), (std::vector<int>{2, 1, 0, 0}))
        << "5, 4.5, 4 taken; at 3 tile 0 kept no more exchanges, and neither would the whole run";
    EXPECT_EQ(ShareExchangeRounds(maxima, 2), (std::vector<int>{1, 1, 0, 0}));
    EXPECT_EQ(ShareExchangeRounds(maxima, 0), (std::vector<int>{0, 0, 0, 0}));
    EXPECT_EQ(ShareExchangeRounds({{3, 2}, {3, 1}}, 16), (std::vector<int>{1, 1}))
        << "equal maxima: the first tile, then the next worst";
    EXPECT_EQ(ShareExchangeRounds({{2}, {}}, 16), (std::vector<int>{0, 0})) << "no exchange kept anywhere";
}

TEST(TargetShare, AnOutcomeIsReadBackOrRefusedWithTheFileNamed)
{
    const std::string dir = ::testing::TempDir() + "gstile_outcome";
    ASSERT_EQ(std::system(("mkdir -p " + dir).c_str()), 0);
    std::string error;
    TileOutcome outcome;
    outcome.target = 120;
    outcome.owned = 80;
    outcome.rounds = 3;
    outcome.maxima = {0.5, 0.25, 0.25, 0.125};
    outcome.entry.distances = {0.125, 0.1, 0.0999999999999999};
    outcome.entry.normalErrors = {1.25, 0.75, 0.5};
    ASSERT_TRUE(WriteOutcome(dir, 7, outcome, error)) << error;
    TileOutcome read;
    ASSERT_TRUE(ReadOutcome(dir, 7, read, error)) << error;
    EXPECT_EQ(read.target, 120u);
    EXPECT_EQ(read.owned, 80u);
    EXPECT_EQ(read.rounds, 3);
    EXPECT_EQ(read.maxima, outcome.maxima);
    EXPECT_EQ(read.entry.distances, outcome.entry.distances) << "every bit of the figures";
    EXPECT_EQ(read.entry.normalErrors, outcome.entry.normalErrors);
    EXPECT_FALSE(read.limits.given);
    outcome.limits = {true, 0.1 / 3, 0.7};
    ASSERT_TRUE(WriteOutcome(dir, 7, outcome, error)) << error;
    ASSERT_TRUE(ReadOutcome(dir, 7, read, error)) << error;
    EXPECT_TRUE(read.limits == outcome.limits) << "the limits a run took, compared exactly with the shares'";
    const auto refused = [&](const std::string &text, const char *what) {
        std::ofstream(dir + "/tile_000007.kept") << text;
        TileOutcome r;
        std::string e;
        EXPECT_FALSE(ReadOutcome(dir, 7, r, e)) << what;
        EXPECT_NE(e.find("tile_000007.kept"), std::string::npos) << what << ": " << e;
    };
    const std::string reports = ", \"highest_distances\": [], \"highest_normal_errors\": []}";
    refused("{\"target\": 120, \"owned\": 80, \"rounds\": 1, \"maxima\": [0.5, 0.6]" + reports, "a maximum that rises");
    refused("{\"target\": 120, \"owned\": 80, \"rounds\": 1, \"maxima\": [-0.5]" + reports, "a negative maximum");
    refused("{\"target\": 120, \"owned\": 80, \"rounds\": -2, \"maxima\": []" + reports, "rounds out of range");
    refused("{\"target\": 120, \"owned\": 80, \"maxima\": []" + reports, "no rounds");
    refused("{\"target\": 120, \"owned\": 80, \"rounds\": 1, \"maxima\": []}", "no report of its highest figures");
    refused("{\"target\": 120, \"owned\": 80, \"rounds\": 1, \"maxima\": [], \"highest_distances\": [0.1, 0.2], "
            "\"highest_normal_errors\": []}", "highest figures not highest first");
    refused("{\"target\": 120, \"owned\": 80, \"rounds\": 1, \"maxima\": [], \"highest_distances\": [], "
            "\"highest_normal_errors\": [-0.5]}", "a negative normal error");
    refused("{\"target\": 120, \"owned\": 80, \"rounds\": 1, \"maxima\": [], \"crease_fit_limits\": {\"distance\": -1, "
            "\"normal_error\": 1}" + reports, "a negative limit");
}

// The tiles' reports of their highest figures hold the whole scan's 99.9th percentiles: the
// limits gathered from them equal the percentiles of all the figures, wherever the highest lie.
TEST(TargetShare, TheCreaseFitLimitsAreTheWholeScansFromTheTilesReports)
{
    EXPECT_EQ(HighestToReport(437645), 438u) << "the dragon: its 99.9th percentile is the 438th highest";
    EXPECT_EQ(HighestToReport(1000), 2u) << "the 999th of 1,000 from below";
    EXPECT_EQ(HighestToReport(0), 0u);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(0, 1);
    const std::uint64_t points = 30000; // a tile of 10,000 points and one of 20,000 ...
    std::vector<double> all, allNormal;
    std::vector<TileOutcome> outcomes(3);
    const std::size_t report = HighestToReport(points);
    for (std::size_t t = 0; t < 2; ++t) {
        std::vector<double> d(10000 * (t + 1)), n(d.size());
        // ... the first holding most of the highest distances, the second most of the highest normal errors.
        for (double &v : d) v = uniform(random) * (t == 0 ? 2 : 1);
        for (double &v : n) v = uniform(random) * (t == 1 ? 2 : 1);
        all.insert(all.end(), d.begin(), d.end());
        allNormal.insert(allNormal.end(), n.begin(), n.end());
        std::sort(d.rbegin(), d.rend());
        std::sort(n.rbegin(), n.rend());
        outcomes[t].entry.distances.assign(d.begin(), d.begin() + std::ptrdiff_t(report));
        outcomes[t].entry.normalErrors.assign(n.begin(), n.begin() + std::ptrdiff_t(report));
    }
    outcomes[2].maxima = {9.0}; // a tile without a report (no crease fit made) is passed over
    outcomes[2].entry.normalErrors = {9.0};
    const vcg::gaussphere::CreaseFitLimits limits = WholeScanCreaseFitLimits(outcomes, points);
    ASSERT_TRUE(limits.given);
    EXPECT_EQ(limits.distance, vcg::gaussphere::NearestRankPercentile(all, 99.9));
    EXPECT_EQ(limits.normalError, vcg::gaussphere::NearestRankPercentile(allNormal, 99.9));
    EXPECT_FALSE(WholeScanCreaseFitLimits({outcomes[2]}, points).given) << "no report: each tile judges by its own";

}

TEST(TargetShare, AMissedShareGetsACountBetweenTheCountsTried)
{
    TileShare share;
    share.owned = 100;
    share.target = 300;
    // 300 kept 90: the ratio of made to owned (300 / 90) carries the 10 missing to 34 more.
    ASSERT_TRUE(AdjustShare(share, {300, 90}, 10000));
    EXPECT_EQ(share.target, 334u);
    // 334 kept 104: between 300 (90) and 334 (104), 10 / 14 of the way.
    ASSERT_TRUE(AdjustShare(share, {334, 104}, 10000));
    EXPECT_EQ(share.target, 324u);
    // 324 kept the share: done.
    EXPECT_FALSE(AdjustShare(share, {324, 100}, 10000));
    EXPECT_EQ(share.target, 324u);
    EXPECT_EQ(share.tried.size(), 3u);

    TileShare capped;
    capped.owned = 50;
    capped.target = 90;
    EXPECT_TRUE(AdjustShare(capped, {90, 10}, 120)) << "far too few: up to the tile's points";
    EXPECT_EQ(capped.target, 120u);
    EXPECT_FALSE(AdjustShare(capped, {120, 20}, 120)) << "at the tile's points nothing is left to try";

    // No count lies between 40 (kept 9) and 41: the nearest of them runs (again).
    TileShare between;
    between.owned = 10;
    between.tried = {{40, 9}};
    between.target = 41;
    ASSERT_TRUE(AdjustShare(between, {41, 12}, 1000));
    EXPECT_EQ(between.target, 40u) << "40 missed by 1, 41 by 2";
    TileShare tie = between;
    tie.tried = {{40, 9}};
    tie.target = 41;
    EXPECT_FALSE(AdjustShare(tie, {41, 11}, 1000)) << "both missed by 1: the later, just run, stays";
    EXPECT_EQ(tie.target, 41u);
}

TEST(TargetShare, AfterItsRoundsATileKeepsTheNearestCountTried)
{
    TileShare share;
    share.owned = 20;
    share.target = 100;
    // A tile whose every count keeps more than its share (its halo moves its level): deterministic
    // runs, none on the share, so the rounds end at the nearest count tried.
    const auto kept = [](std::uint64_t target) { return 25 + target % 7; };
    std::size_t runs = 1;
    while (runs < 10 && AdjustShare(share, {share.target, kept(share.target)}, 1000)) ++runs;
    EXPECT_EQ(share.tried.size(), kAdjustRounds + 1) << "the first count and kAdjustRounds new ones";
    EXPECT_LE(runs, kAdjustRounds + 2) << "and at most one more run, of the nearest";
    for (const TileTrial &t : share.tried) EXPECT_LE(kept(share.target), t.owned);
}

/// Per tile of `manifest`, the surfels of `result` (of the whole input) it would own: those whose
/// anchor, the member with the smallest input index, lies in its core.
std::vector<std::uint64_t> OwnedPerTile(const vcg::gaussphere::ResamplingResult &result,
                                        const vcg::gaussphere::OrientedPointMesh &points, const Manifest &manifest)
{
    std::vector<int> anchor(result.surfels.size(), -1);
    for (std::size_t v = 0; v < result.representative.size(); ++v) {
        const int s = result.representative[v];
        if (s >= 0 && anchor[std::size_t(s)] < 0) anchor[std::size_t(s)] = int(v);
    }
    std::vector<std::uint64_t> owned(manifest.tiles.size(), 0);
    for (const int v : anchor) {
        if (v < 0) continue; // a surfel without members (none: ResamplePointSet's postcondition)
        const float p[3] = {points.vert[std::size_t(v)].P()[0], points.vert[std::size_t(v)].P()[1],
                            points.vert[std::size_t(v)].P()[2]};
        const TileEntry *tile = manifest.Find(manifest.grid.IdOf(manifest.grid.CellOf(p)));
        ++owned[std::size_t(tile - manifest.tiles.data())];
    }
    return owned;
}

// Below the coarsest level's count the whole run merges its cheapest pairs first; the tiles'
// merges taken in cost order give each tile the surfels the whole run leaves in its core, where
// shares in proportion to the tiles' clusters would not.
TEST(TiledTarget, MergesAreSharedWhereTheWholeRunMakesThem)
{
    const std::string dir = ::testing::TempDir() + "gstile_bunny_merged";
    SplitOptions options;
    options.tilePoints = 20000;
    options.param.targetCount = 500;
    options.param.maxErrorExchanges = 0;
    Manifest manifest;
    std::string error;
    ASSERT_TRUE(Split(kBunny, dir, options, manifest, [](const std::string &) {}, error)) << error;
    std::vector<int> ids;
    for (int round = 0; TilesToProbe(dir, manifest, ids, error) && !ids.empty(); ++round) {
        ASSERT_LE(round, 10);
        for (const int id : ids) {
            ProbeFigures probe;
            ASSERT_TRUE(ProbeTile(dir, manifest, id, probe, error)) << error;
        }
    }
    ShareDecision decision;
    bool written = false;
    ASSERT_TRUE(error.empty() && WriteShares(dir, manifest, decision, written, error)) << error;
    ASSERT_TRUE(decision.shared);

    vcg::gaussphere::OrientedPointMesh bunny;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(kBunny, bunny, error)) << error;
    const vcg::gaussphere::ResamplingResult whole = vcg::gaussphere::ResamplePointSet(bunny, options.param);
    ASSERT_GT(whole.stats.mergesForTarget, 1000) << "the target lies far below the coarsest level";
    EXPECT_EQ(decision.shares.level, whole.stats.levelUsed);
    const std::vector<std::uint64_t> wholeOwned = OwnedPerTile(whole, bunny, manifest);
    ASSERT_GE(wholeOwned.size(), 3u);
    std::uint64_t missed = 0;
    for (std::size_t t = 0; t < wholeOwned.size(); ++t) {
        const std::uint64_t share = decision.shares.tiles[t].owned;
        missed += share > wholeOwned[t] ? share - wholeOwned[t] : wholeOwned[t] - share;
    }
    EXPECT_LE(missed, 10u) << "the shares against the whole run's surfels per tile, summed";
    // Shares in proportion to the tiles' owned clusters at the level miss by far more.
    double proportionalMiss = 0;
    std::uint64_t ownedAtLevel = 0;
    std::vector<TileProbe> probes;
    ASSERT_TRUE(ReadProbes(dir, manifest, probes, error)) << error;
    for (const TileProbe &p : probes) ownedAtLevel += p.At(decision.shares.level)->owned;
    for (std::size_t t = 0; t < probes.size(); ++t)
        proportionalMiss += std::abs(500.0 * double(probes[t].At(decision.shares.level)->owned) / double(ownedAtLevel) -
                                     double(wholeOwned[t]));
    EXPECT_GT(proportionalMiss, 3.0 * double(missed) + 10.0);
    // The merge records tell which merges take away an owned cluster: the runs keep the shares.
    TileRunFigures figures;
    std::uint64_t kept = 0;
    for (std::size_t t = 0; t < manifest.tiles.size(); ++t) {
        ASSERT_TRUE(RunTile(dir, manifest, manifest.tiles[t].id, figures, error)) << error;
        EXPECT_EQ(std::uint64_t(figures.owned), decision.shares.tiles[t].owned) << "tile " << manifest.tiles[t].id;
        kept += std::uint64_t(figures.owned);
    }
    EXPECT_EQ(kept, 500u);
}

TEST(TiledTarget, TheBunnysTilesMeetATargetSharedAsTheWholeRunSpendsIt)
{
    const std::string dir = ::testing::TempDir() + "gstile_bunny_target";
    SplitOptions options;
    options.tilePoints = 20000;
    options.param.targetCount = 3000;
    Manifest manifest;
    std::string error;
    ASSERT_TRUE(Split(kBunny, dir, options, manifest, [](const std::string &) {}, error)) << error;
    ASSERT_EQ(manifest.targetCount, 3000u);
    TileRunFigures figures;
    ASSERT_FALSE(RunTile(dir, manifest, manifest.tiles[0].id, figures, error)) << "a run before the share";
    EXPECT_NE(error.find("gstile probe"), std::string::npos) << error;

    error.clear();
    std::vector<int> ids;
    int probeRounds = 0;
    for (; TilesToProbe(dir, manifest, ids, error) && !ids.empty(); ++probeRounds) {
        for (const int id : ids) {
            ProbeFigures probe;
            ASSERT_TRUE(ProbeTile(dir, manifest, id, probe, error)) << error;
            ASSERT_TRUE(probe.probed);
            if (id == ids.back()) continue; // the round is complete: a probe again would start the next
            ProbeFigures again;
            ASSERT_TRUE(ProbeTile(dir, manifest, id, again, error)) << error;
            EXPECT_FALSE(again.probed) << "a tile probed has what this round needs";
        }
        ASSERT_LE(probeRounds, 10);
    }
    ASSERT_TRUE(error.empty()) << error;
    EXPECT_GE(probeRounds, 2) << "the level, then the splits there";
    ShareDecision decision;
    bool written = false;
    ASSERT_TRUE(WriteShares(dir, manifest, decision, written, error)) << error;
    ASSERT_TRUE(decision.shared && written);
    std::uint64_t shared = 0;
    for (const TileShare &share : decision.shares.tiles) shared += share.owned;
    EXPECT_EQ(shared, 3000u);
    vcg::gaussphere::OrientedPointMesh bunny;
    vcg::gaussphere::ResamplingParams whole;
    whole.targetCount = 3000;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(kBunny, bunny, error)) << error;
    EXPECT_EQ(decision.shares.level, vcg::gaussphere::ResamplePointSet(bunny, whole).stats.levelUsed)
        << "the level of the whole run";
    ASSERT_TRUE(WriteShares(dir, manifest, decision, written, error)) << error;
    EXPECT_FALSE(written) << "the shares are written once";
    for (const TileEntry &t : manifest.tiles) ASSERT_TRUE(RunTile(dir, manifest, t.id, figures, error)) << error;
    std::vector<int> pending;
    ASSERT_TRUE(PendingTiles(dir, manifest, pending, error)) << error;
    EXPECT_TRUE(pending.empty()) << "every tile ran at its share's count";
    AdjustFigures first;
    ASSERT_TRUE(AdjustShares(dir, manifest, first, error)) << error;
    ASSERT_TRUE(PendingTiles(dir, manifest, pending, error)) << error;
    EXPECT_EQ(pending, first.rerun) << "the tiles given a new count are left to run";
    // The whole run's 16 rounds of exchanges are shared once: a tile takes no more rounds than it
    // recorded exchanges, and its runs from then on make at most its part.
    Shares sharedRounds;
    ASSERT_TRUE(ReadShares(dir, sharedRounds, error)) << error;
    EXPECT_TRUE(sharedRounds.RoundsShared());
    int roundsInAll = 0;
    for (const TileShare &share : sharedRounds.tiles) {
        EXPECT_GE(share.rounds, 0) << "tile " << share.id;
        roundsInAll += share.rounds;
    }
    EXPECT_GT(roundsInAll, 0);
    EXPECT_LE(roundsInAll, options.param.maxErrorExchanges);
    EXPECT_FALSE(sharedRounds.creaseFitLimits.given) << "the limits wait for every tile's run at its rounds";
    std::uint64_t rounds = 0, seamRound = 0;
    for (AdjustFigures round = first; !round.rerun.empty(); ++rounds) {
        for (const int id : round.rerun) ASSERT_TRUE(RunTile(dir, manifest, id, figures, error)) << error;
        ASSERT_TRUE(AdjustShares(dir, manifest, round, error)) << error;
        if (!round.seamTaken) continue;
        EXPECT_EQ(seamRound, 0u) << "the seam step is taken once";
        seamRound = rounds + 1;
        EXPECT_EQ(round.rerun.size(), manifest.tiles.size()) << "every tile runs again with its neighbours' snapshots";
        for (const TileEntry &t : manifest.tiles)
            EXPECT_TRUE(std::ifstream(TilePath(dir, t.id, ".seam"))) << "tile " << t.id << "'s snapshot";
        // Each tile's seam rounds lower its points to the largest the other tiles' rounds reached.
        Shares atSeam;
        ASSERT_TRUE(ReadShares(dir, atSeam, error)) << error;
        std::vector<double> reached;
        for (const TileShare &share : atSeam.tiles) {
            TileOutcome outcome;
            ASSERT_TRUE(ReadOutcome(dir, share.id, outcome, error)) << error;
            reached.push_back(outcome.maxima.empty() ? 0.0 : outcome.maxima.back());
        }
        for (std::size_t t = 0; t < atSeam.tiles.size(); ++t) {
            double others = 0;
            for (std::size_t o = 0; o < reached.size(); ++o)
                if (o != t) others = std::max(others, reached[o]);
            EXPECT_EQ(atSeam.tiles[t].seamTarget, others) << "tile " << atSeam.tiles[t].id;
        }
    }
    EXPECT_GT(seamRound, 1u) << "after the rounds of exchanges and the crease fit limits are shared";
    EXPECT_LE(rounds, 2 * kAdjustRounds + 3) << "a tile's new counts, their nearest, a run for its rounds, the seam "
                                                "step and new counts after it";
    ASSERT_TRUE(ReadShares(dir, sharedRounds, error)) << error;
    EXPECT_TRUE(sharedRounds.seam);
    ASSERT_TRUE(sharedRounds.creaseFitLimits.given);
    EXPECT_GT(sharedRounds.creaseFitLimits.distance, 0);
    EXPECT_GT(sharedRounds.creaseFitLimits.normalError, 0);
    for (const TileShare &share : sharedRounds.tiles) {
        TileOutcome outcome;
        ASSERT_TRUE(ReadOutcome(dir, share.id, outcome, error)) << error;
        // At its part's rounds, or at all of them where it kept no more exchanges than its part.
        EXPECT_TRUE(RanAtRounds(outcome, share)) << "tile " << share.id << ": rounds " << outcome.rounds;
        EXPECT_LE(outcome.maxima.size(), std::size_t(share.rounds) + 1) << "tile " << share.id;
        EXPECT_TRUE(outcome.limits == sharedRounds.creaseFitLimits) << "tile " << share.id << ": the scan's crease fit limits";
        EXPECT_TRUE(outcome.seam) << "tile " << share.id << ": run after the seam step";
    }
    MergeFigures merged;
    ASSERT_TRUE(Merge(dir, manifest, dir + "/merged.surfel", merged, error)) << error;
    // Tiles of 20,000 points whose halos are larger than their cores: the first runs' owned counts
    // miss the shares, the adjusted ones meet the target within 0.2 %.
    EXPECT_NE(first.kept, 3000u);
    EXPECT_NEAR(double(merged.surfels - merged.rescued), 3000.0, 6.0);
    EXPECT_LE(merged.rescued, 30u) << "halos of 24 spacings: few border points no tile keeps nor covers";
    EXPECT_NEAR(double(merged.members), double(manifest.points), 0.005 * manifest.points);

    // A damaged snapshot (a NaN member count in each) stops a tile's run with the file named and
    // the way to start the target's steps again; the tile's result stays as it was.
    for (const TileEntry &t : manifest.tiles) {
        std::vector<surfel_io::SurfelRecord> records;
        ASSERT_TRUE(surfel_io::readSurfelFile(TilePath(dir, t.id, ".seam"), records, error)) << error;
        ASSERT_FALSE(records.empty());
        records[0].quality = std::numeric_limits<float>::quiet_NaN();
        ASSERT_TRUE(surfel_io::writeSurfelFile(TilePath(dir, t.id, ".seam"), records, error)) << error;
    }
    const int firstTile = manifest.tiles.front().id;
    std::vector<surfel_io::SurfelRecord> before, after;
    ASSERT_TRUE(surfel_io::readSurfelFile(TilePath(dir, firstTile, ".surfel"), before, error)) << error;
    error.clear();
    EXPECT_FALSE(RunTile(dir, manifest, firstTile, figures, error));
    EXPECT_NE(error.find(".seam: surfel 0 is not one a tile's run writes"), std::string::npos) << error;
    EXPECT_NE(error.find("run the tiles from gstile share on"), std::string::npos) << error;
    ASSERT_TRUE(surfel_io::readSurfelFile(TilePath(dir, firstTile, ".surfel"), after, error)) << error;
    EXPECT_TRUE(before == after) << "the result of the run that stopped is kept";
}

} // namespace
