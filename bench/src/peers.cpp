#include "peers.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <CGAL/grid_simplify_point_set.h>
#include <CGAL/hierarchy_simplify_point_set.h>
#include <CGAL/property_map.h>

namespace gsbench {

namespace {

/// Indices of [first, last), the points a CGAL simplification kept.
template <class Iterator>
std::vector<int> KeptIndices(Iterator first, Iterator last)
{
    std::vector<int> kept;
    kept.reserve(size_t(std::distance(first, last)));
    for (Iterator it = first; it != last; ++it) kept.push_back(it->second);
    return kept;
}

/// Runs `simplify` on a copy of `points` (CGAL moves the removed points to the end of the
/// range and returns where they start), timing the call alone.
template <class Points, class Simplify>
std::vector<int> RunOnCopy(const Points &points, double *seconds, Simplify simplify)
{
    Points work = points;
    const auto start = std::chrono::steady_clock::now();
    const auto end = simplify(work);
    if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return KeptIndices(work.begin(), end);
}

} // namespace

std::string HierarchyParams::ToString() const
{
    std::ostringstream s;
    s << "size=" << maxClusterSize << " var_max=" << std::setprecision(4) << maxVariation;
    return s.str();
}

CgalPointSet::CgalPointSet(const PointMesh &mesh)
{
    points_.reserve(mesh.vert.size());
    for (size_t i = 0; i < mesh.vert.size(); ++i) {
        const auto &p = mesh.vert[i].cP();
        points_.emplace_back(Kernel::Point_3(p[0], p[1], p[2]), int(i));
    }
}

std::vector<int> CgalPointSet::Hierarchy(const HierarchyParams &param, double *seconds) const
{
    return RunOnCopy(points_, seconds, [&](std::vector<IndexedPoint> &work) {
        return CGAL::hierarchy_simplify_point_set(
            work, CGAL::parameters::point_map(CGAL::First_of_pair_property_map<IndexedPoint>())
                      .size(unsigned(param.maxClusterSize))
                      .maximum_variation(param.maxVariation));
    });
}

std::vector<int> CgalPointSet::Grid(double cellSize, double *seconds) const
{
    return RunOnCopy(points_, seconds, [&](std::vector<IndexedPoint> &work) {
        return CGAL::grid_simplify_point_set(
            work, cellSize, CGAL::parameters::point_map(CGAL::First_of_pair_property_map<IndexedPoint>()));
    });
}

HierarchyMatch MatchHierarchy(const CgalPointSet &points, int target, double tolerance)
{
    HierarchyMatch result;
    // Mean cluster size N / target; the count is roughly N / (0.5..1 x size).
    const double meanCluster = double(points.Size()) / target;
    result.match = MatchCount(
        [&](double size) {
            return int(points.Hierarchy({int(size), 1.0 / 3.0}).size());
        },
        std::max(1.0, meanCluster / 4), 4 * meanCluster + 2, target, tolerance, SearchDomain::Integer);
    result.param.maxClusterSize = int(result.match.parameter);
    if (result.match.withinTolerance || result.match.parameterBelow == 0) return result;

    // Stage 2: at the size giving fewer points than the target, split by variation as well.
    const int evaluationsSoFar = result.match.evaluations;
    result = MatchHierarchyVariation(points, int(result.match.parameterBelow), target, tolerance);
    result.match.evaluations += evaluationsSoFar;
    return result;
}

HierarchyMatch MatchHierarchyVariation(const CgalPointSet &points, int maxClusterSize, int target, double tolerance)
{
    HierarchyMatch result;
    result.match = MatchCount(
        [&](double variation) {
            return int(points.Hierarchy({maxClusterSize, variation}).size());
        },
        1e-4, 1.0 / 3.0, target, tolerance, SearchDomain::Positive);
    result.param = {maxClusterSize, result.match.parameter};
    return result;
}

CountMatch MatchGrid(const CgalPointSet &points, double diagonal, int target, double tolerance)
{
    return MatchCount([&](double cell) { return int(points.Grid(cell).size()); }, 1e-4 * diagonal,
                      0.1 * diagonal, target, tolerance, SearchDomain::Positive);
}

MeshLabPoisson::MeshLabPoisson(std::string meshlabserver, std::string input, double diagonal, std::string workDir)
    : meshlabserver_(std::move(meshlabserver)), input_(std::move(input)), workDir_(std::move(workDir)),
      diagonal_(diagonal)
{
}

std::string MeshLabPoisson::WriteScript(double radius) const
{
    // meshlabserver 2020.09 aborts on a script that does not list every parameter of the
    // filter (docs: PLATFORM.md), so all five are written. RichAbsPerc takes absolute values.
    const std::string path = workDir_ + "/poisson.mlx";
    std::ofstream mlx(path);
    mlx << std::setprecision(9)
        << "<!DOCTYPE FilterScript>\n<FilterScript>\n"
        << " <filter name=\"Point Cloud Simplification\">\n"
        << "  <Param type=\"RichInt\" value=\"1000\" name=\"SampleNum\"/>\n"
        << "  <Param type=\"RichAbsPerc\" value=\"" << radius << "\" name=\"Radius\" min=\"0\" max=\""
        << diagonal_ << "\"/>\n"
        << "  <Param type=\"RichBool\" value=\"true\" name=\"BestSampleFlag\"/>\n"
        << "  <Param type=\"RichInt\" value=\"10\" name=\"BestSamplePool\"/>\n"
        << "  <Param type=\"RichBool\" value=\"false\" name=\"ExactNumFlag\"/>\n"
        << " </filter>\n</FilterScript>\n";
    if (!mlx) throw std::runtime_error("cannot write " + path);
    return path;
}

ChildRun MeshLabPoisson::Run(double radius, const std::string &output) const
{
    const std::string script = WriteScript(radius);
    const std::string log = workDir_ + "/meshlabserver.log";
    const ChildRun run = RunChild({meshlabserver_, "-i", input_, "-s", script, "-o", output, "-m", "vn"}, log);
    if (run.exitStatus != 0)
        throw std::runtime_error("meshlabserver failed with status " + std::to_string(run.exitStatus) +
                                 " (see " + log + ")");
    return run;
}

CountMatch MeshLabPoisson::Match(int target, double tolerance) const
{
    const std::string output = workDir_ + "/poisson_search.ply";
    // Disks of radius r cover about 0.7 pi r^2 each (MeshLab's own density factor); a bracket
    // from one tenth to ten times a rough guess keeps the number of runs small.
    const double guess = diagonal_ * std::sqrt(0.5 / (0.7 * M_PI * target));
    return MatchCount(
        [&](double radius) {
            Run(radius, output);
            return PlyVertexCount(output);
        },
        guess / 4, guess * 4, target, tolerance, SearchDomain::Positive);
}

} // namespace gsbench
