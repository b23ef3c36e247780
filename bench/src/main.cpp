// gsbench: our Gaussian sphere resampler against its peers at equal output counts, with the
// error metric of the paper's section 5.2 (vcg_ext/surfel_error).
//
//   gsbench compare INPUT.ply --name NAME [--level N] [--methods LIST] [--threads LIST]
//                   [--runs R] [--csv OUT.csv] [--work DIR] [--meshlabserver PATH]
//                   [--tolerance F] [--no-process] [--trim-heap] [--target-percent P] [--max-error E]
//                   [--seed-salt S]
//     Runs our resampler at level N (default 8), tunes every peer in LIST to the same count
//     (+- F, default 0.02), measures each output, and appends one CSV row per method to OUT.csv
//     (default stdout). LIST (default: all) is a comma-separated subset of
//       ours             our resampler; one row per thread count in --threads (default 1,2)
//       ours-circular    our surfel centres measured as plain points: no ellipses, no
//                        point-to-surfel map (shows what the metric owes to the ellipses)
//       cgal-hierarchy   CGAL hierarchy_simplify_point_set (Pauly et al. 2002), matched by
//                        cluster size, then by variation (see MatchHierarchy)
//       cgal-hierarchy-var  the same, cluster size capped at 4x the mean, matched by variation
//       cgal-grid        CGAL grid_simplify_point_set
//       meshlab-poisson  MeshLab's Point Cloud Simplification through meshlabserver (needs
//                        --meshlabserver and an X display)
//       floor            S' = S, the metric's floor
//     A CGAL peer that cannot be matched to our count is followed by a row "ours@PEER": ours
//     at the peer's count, exact through TargetCount, measured but not timed.
//     Times: "alg" is the median of R (default 3) in-process runs of the algorithm alone, after
//     loading, taken in rounds that run each timed method once in turn (InterleavedTimings:
//     the ratios hold while a shared machine's load changes; --trim-heap returns the heap's free
//     memory to the system before each run, so that every run faults its heap pages in as a
//     first call does); "process" is the median wall time of R runs of `gsbench run` (load, run, save)
//     or of meshlabserver, whose peak resident memory is reported too. --no-process skips the
//     process runs (the figure-7 sweep needs only counts and errors).
//     Beyond the paper (ResamplingParams::targetCount, maxErrorFraction), either or both:
//       --target-percent P  ours outputs exactly round(P % of the input) surfels (targetCount;
//                           the level N is where its level search starts)
//       --max-error E       ours splits clusters until every point lies within E x bbox
//                           diagonal of its own surfel's plane, then of the blended surface
//                           the metric projects on, splitting clusters and narrowing one-point surfels (maxErrorFraction)
//     The peers are matched to ours' resulting count as always. With --max-error every row
//     also reports the fraction of input points whose metric distance D* exceeds E, and ours'
//     rows the largest distance to the own surfel's plane, the splits of each stage and the
//     points ours reports beyond E (those the blend cannot bring closer).
//     --seed-salt S (default 0) runs ours with ResamplingTuning::seedSalt = S: another, equally
//     valid, order of its seeds, whose error figures show how far they move by chance
//     (bench/seed_spread.py).
//
//   gsbench run METHOD INPUT.ply OUTPUT.ply [--level N] [--threads T] [--size S]
//               [--variation V] [--cell C] [--target-count C] [--max-error E] [--seed-salt S]
//     The process measured by compare: load, one method, save, nothing else.
//
//   gsbench export INPUT.ply --count N --out PREFIX [--methods LIST] [--meshlabserver PATH]
//                  [--work DIR] [--tolerance F] [--csv OUT.csv]
//     Matches every peer in LIST (default cgal-hierarchy,cgal-grid,meshlab-poisson) to N points
//     (+- F, default 0.02) by compare's searches and writes its output, input points with their
//     normals, to PREFIX_METHOD.ply; appends one CSV row per peer (count, parameters, whether
//     it matched) to OUT.csv (default stdout). The downstream benchmark reconstructs surfaces
//     from these files (scripts/bench_downstream.sh).
//
//   gsbench knn INPUT.ply [--k K] [--threads T] [--runs R]
//     Prints the median seconds over R runs (default 5) of the k nearest neighbours (default 16,
//     the resampler's default) of every point by nanoflann's kd-tree, its build included, on T
//     threads (default 2): the paper's first step by a standard library, beside the whole
//     filter's time (bench/filter_speed.sh).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <omp.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <sys/stat.h>

#include <vcg_ext/gaussphere/resampling.h>
#include <vcg_ext/gaussphere/surfels/surfel_mesh.h>

#include "child_process.h"
#include "knn_reference.h"
#include "peers.h"
#include "point_sets.h"

using namespace gsbench;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// Command line

/// "--key value" pairs after the positional arguments.
class Options
{
public:
    Options(int argc, char **argv, int first)
    {
        for (int a = first; a < argc; ++a) {
            const std::string key = argv[a];
            if (key.rfind("--", 0) != 0) throw std::invalid_argument("unexpected argument " + key);
            if (key == "--no-process" || key == "--trim-heap") { values_[key] = "1"; continue; }
            if (a + 1 >= argc) throw std::invalid_argument(key + " needs a value");
            values_[key] = argv[++a];
        }
    }
    std::string Get(const std::string &key, const std::string &fallback) const
    {
        used_.insert(key);
        const auto it = values_.find(key);
        return it == values_.end() ? fallback : it->second;
    }
    int Int(const std::string &key, int fallback) const { return std::stoi(Get(key, std::to_string(fallback))); }
    double Real(const std::string &key, double fallback) const
    {
        const std::string v = Get(key, "");
        return v.empty() ? fallback : std::stod(v);
    }
    bool Has(const std::string &key) const { used_.insert(key); return values_.count(key) > 0; }
    /// Call after every Get: rejects misspelt options instead of ignoring them.
    void RejectUnused() const
    {
        for (const auto &kv : values_)
            if (!used_.count(kv.first)) throw std::invalid_argument("unknown option " + kv.first);
    }

private:
    std::map<std::string, std::string> values_;
    mutable std::set<std::string> used_;
};

/// --seed-salt: ResamplingTuning::seedSalt, a 32-bit unsigned number (default 0).
std::uint32_t SeedSalt(const Options &opt)
{
    const unsigned long long salt = std::stoull(opt.Get("--seed-salt", "0"));
    if (salt > 0xffffffffull) throw std::invalid_argument("--seed-salt must be below 2^32");
    return std::uint32_t(salt);
}

std::vector<std::string> Split(const std::string &list)
{
    std::vector<std::string> items;
    std::istringstream in(list);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) items.push_back(item);
    return items;
}

double Median(std::vector<double> values)
{
    if (values.empty()) return kNaN;
    std::sort(values.begin(), values.end());
    const size_t m = values.size() / 2;
    return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

/// Returns the heap's free memory to the system (glibc; elsewhere nothing to do).
void TrimHeap()
{
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}

/// The in-process timings of the methods compared, taken in rounds: each round runs every timed
/// method once, in turn, so that a change in the load of a shared machine between one method's
/// runs and the next one's weighs on all of them alike and their ratios hold. Each method gets
/// the median of its rounds.
class InterleavedTimings
{
public:
    /// `timedRun` runs the method of result row `row` once and returns its own duration in seconds.
    void Add(size_t row, std::function<double()> timedRun) { runs_.push_back({row, std::move(timedRun)}); }

    /// Runs `rounds` rounds; returns (row, median seconds) for every method added. With
    /// `trimHeap`, the heap's free memory goes back to the system before every run (malloc_trim):
    /// each run faults its heap pages in afresh, as a first call in a process does.
    std::vector<std::pair<size_t, double>> Run(int rounds, bool trimHeap) const
    {
        std::vector<std::vector<double>> seconds(runs_.size());
        // Each round starts one method later, so that no method always follows the same one.
        for (int round = 0; round < rounds; ++round)
            for (size_t step = 0; step < runs_.size(); ++step) {
                const size_t m = (size_t(round) + step) % runs_.size();
                if (trimHeap) TrimHeap();
                seconds[m].push_back(runs_[m].second());
            }
        std::vector<std::pair<size_t, double>> medians;
        for (size_t m = 0; m < runs_.size(); ++m) medians.push_back({runs_[m].first, Median(seconds[m])});
        return medians;
    }

private:
    std::vector<std::pair<size_t, std::function<double()>>> runs_;
};

// ---------------------------------------------------------------------------------------------
// Our resampler

/// What ours is asked for: the paper's level n, optionally an exact count and an error bound.
struct OursConfig
{
    int level = 8;
    int targetCount = 0;      ///< ResamplingParams::targetCount (0 = off)
    double maxError = 0;      ///< ResamplingParams::maxErrorFraction (0 = off)
    std::uint32_t seedSalt = 0; ///< ResamplingTuning::seedSalt
};

vcg::gaussphere::ResamplingResult RunOurs(const PointMesh &input, const OursConfig &config, int threads, double *seconds)
{
    vcg::gaussphere::ResamplingParams param;
    param.subdivisionLevel = config.level;
    param.targetCount = config.targetCount;
    param.maxErrorFraction = config.maxError;
    param.tuning.seedSalt = config.seedSalt;
    omp_set_num_threads(threads);
    const auto start = std::chrono::steady_clock::now();
    vcg::gaussphere::ResamplingResult result = vcg::gaussphere::ResamplePointSet(input, param);
    if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

void ToSimplifiedSet(const vcg::gaussphere::ResamplingResult &result, SimplifiedSet &set)
{
    vcg::gaussphere::WriteSurfels(result.surfels, set.mesh);
    set.major.clear();
    set.minor.clear();
    set.blendScale.clear();
    for (const auto &s : result.surfels) {
        set.major.push_back(s.majorAxis);
        set.minor.push_back(s.minorAxis);
        set.blendScale.push_back(s.blendScale);
    }
    set.representative.assign(result.representative.begin(), result.representative.end());
}

/// Largest distance of an input point to the plane of its own surfel (centre, normal), over the
/// bounding-box diagonal of the input: what maxErrorFraction bounds first (then D*, the distance
/// to the blended surface of all surfels).
double MaxOwnPlaneDistance(const PointMesh &input, const vcg::gaussphere::ResamplingResult &result)
{
    double worst = 0;
    for (size_t i = 0; i < input.vert.size(); ++i) {
        const int s = result.representative[i];
        if (s < 0 || input.vert[i].IsD()) continue;
        const auto &surfel = result.surfels[s];
        const vcg::Point3d offset = vcg::Point3d::Construct(input.vert[i].cP()) - vcg::Point3d::Construct(surfel.position);
        worst = std::max(worst, std::abs(offset.dot(vcg::Point3d::Construct(surfel.normal))));
    }
    return worst / input.bbox.Diag();
}

// ---------------------------------------------------------------------------------------------
// Results

/// One line of the raw table: one method on one model at one level.
struct Row
{
    std::string model, method, parameters;
    int inputPoints = 0, level = 0, threads = 0, points = 0, evaluations = 0;
    bool matched = true;
    double timeAlg = kNaN, timeProcess = kNaN, peakMegabytes = kNaN;
    bool measured = false;
    vcg::gaussphere::metric::SurfelErrorStats error;
    // Beyond the paper: the run's targets (0 = off), and what they gave.
    double targetPercent = 0, maxError = 0;
    int targetPoints = 0;
    int levelUsed = 0, splitsForErrorBound = 0, splitsForTarget = 0, mergesForTarget = 0; ///< ours only
    int splitsForSurfaceBound = 0, pointsAboveBound = 0; ///< ours only: ResamplingStats
    double ownPlaneMax = kNaN;      ///< ours only: see MaxOwnPlaneDistance
    double dstarAboveFraction = kNaN; ///< with maxError: fraction of input points with D* > maxError
    int reducedThreadRuns = 0;      ///< ours only: timed runs that took fewer threads than `threads`
                                    ///< (the OpenMP runtime gave fewer)
};

const char *kCsvHeader =
    "model,input_points,level,method,threads,points,percent,parameters,matched,match_evaluations,"
    "time_alg_s,time_process_s,peak_mb,l21_own_rms,l21_own_max,l21_own_p999,l21_blend_rms,"
    "l21_blend_max,l21_blend_p999,dstar_rms,dstar_max,dstar_p999,unconverged,diagonal,"
    "target_percent,target_points,max_error,level_used,splits_error_bound,splits_target,merges_target,"
    "own_plane_max,dstar_above_max_error,splits_surface_bound,points_above_bound,reduced_thread_runs";

std::string Number(double v, int digits = 6)
{
    if (std::isnan(v)) return "";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
    return buffer;
}

std::string CsvLine(const Row &r)
{
    const auto &e = r.error;
    auto err = [&](double v) { return r.measured ? Number(v) : std::string(); };
    std::ostringstream line;
    line << r.model << ',' << r.inputPoints << ',' << r.level << ',' << r.method << ','
         << (r.threads ? std::to_string(r.threads) : "") << ',' << r.points << ','
         << Number(100.0 * r.points / r.inputPoints, 4) << ',' << r.parameters << ','
         << (r.matched ? "yes" : "no") << ',' << r.evaluations << ',' << Number(r.timeAlg, 4) << ','
         << Number(r.timeProcess, 4) << ',' << Number(r.peakMegabytes, 4) << ','
         << err(e.normalToOwnSurfel.rms) << ',' << err(e.normalToOwnSurfel.max) << ','
         << err(e.normalToOwnSurfel.p999) << ',' << err(e.normalToBlended.rms) << ','
         << err(e.normalToBlended.max) << ',' << err(e.normalToBlended.p999) << ','
         << err(e.normalizedDistance.rms) << ',' << err(e.normalizedDistance.max) << ','
         << err(e.normalizedDistance.p999) << ',' << (r.measured ? std::to_string(e.unconvergedCount) : "")
         << ',' << err(e.diagonal);
    const bool ours = r.method.rfind("ours", 0) == 0 && r.method != "ours-circular";
    auto oursInt = [&](int v) { return ours ? std::to_string(v) : std::string(); };
    line << ',' << (r.targetPercent > 0 ? Number(r.targetPercent) : "") << ','
         << (r.targetPoints > 0 ? std::to_string(r.targetPoints) : "") << ','
         << (r.maxError > 0 ? Number(r.maxError) : "") << ',' << oursInt(r.levelUsed) << ','
         << oursInt(r.splitsForErrorBound) << ',' << oursInt(r.splitsForTarget) << ',' << oursInt(r.mergesForTarget)
         << ',' << Number(r.ownPlaneMax) << ',' << Number(r.dstarAboveFraction) << ','
         << oursInt(r.splitsForSurfaceBound) << ',' << oursInt(r.pointsAboveBound) << ','
         << (r.method == "ours" ? std::to_string(r.reducedThreadRuns) : "");
    return line.str();
}

void WriteRows(const std::string &path, const std::vector<Row> &rows)
{
    if (path.empty() || path == "-") {
        std::printf("%s\n", kCsvHeader);
        for (const Row &r : rows) std::printf("%s\n", CsvLine(r).c_str());
        return;
    }
    struct stat st;
    const bool fresh = stat(path.c_str(), &st) != 0 || st.st_size == 0;
    std::ofstream out(path, std::ios::app);
    if (fresh) out << kCsvHeader << '\n';
    for (const Row &r : rows) out << CsvLine(r) << '\n';
    if (!out) throw std::runtime_error("cannot write " + path);
}

void Announce(const Row &r)
{
    if (r.reducedThreadRuns > 0)
        std::fprintf(stderr, "  warning: %d timed run(s) of %s/%dt took fewer threads: other programs kept CPUs busy\n",
                     r.reducedThreadRuns, r.method.c_str(), r.threads);
    std::fprintf(stderr, "  %-16s %8d pts %s | alg %s s, process %s s, %s MB | L21 own %s/%s blend %s/%s | D* %s/%s\n",
                 (r.method + (r.threads ? "/" + std::to_string(r.threads) + "t" : "")).c_str(), r.points,
                 r.parameters.c_str(), Number(r.timeAlg, 3).c_str(), Number(r.timeProcess, 3).c_str(),
                 Number(r.peakMegabytes, 4).c_str(), Number(r.error.normalToOwnSurfel.rms, 3).c_str(),
                 Number(r.error.normalToOwnSurfel.max, 3).c_str(), Number(r.error.normalToBlended.rms, 3).c_str(),
                 Number(r.error.normalToBlended.max, 3).c_str(), Number(r.error.normalizedDistance.rms, 3).c_str(),
                 Number(r.error.normalizedDistance.max, 3).c_str());
}

// ---------------------------------------------------------------------------------------------
// Peers' parameters as the tables show them (lengths over the input's bounding-box diagonal)

std::string GridParameters(const CountMatch &m, double diagonal)
{
    return "cell=" + Number(m.parameter / diagonal, 4) + "xdiag";
}

std::string PoissonParameters(const CountMatch &m, double diagonal)
{
    return "radius=" + Number(m.parameter / diagonal, 4) + "xdiag";
}

// ---------------------------------------------------------------------------------------------
// compare

struct ProcessFigures
{
    double seconds = kNaN, peakMegabytes = kNaN;
};

/// Median wall time and peak memory of `runs` runs of a child process that must succeed.
ProcessFigures MeasureProcess(int runs, const std::function<ChildRun()> &runOnce)
{
    ProcessFigures f;
    std::vector<double> seconds;
    f.peakMegabytes = 0;
    for (int r = 0; r < runs; ++r) {
        const ChildRun run = runOnce();
        if (run.exitStatus != 0) throw std::runtime_error("a measured process failed");
        seconds.push_back(run.wallSeconds);
        f.peakMegabytes = std::max(f.peakMegabytes, run.peakMegabytes);
    }
    f.seconds = Median(seconds);
    return f;
}

int Compare(const std::string &inputPath, const Options &opt)
{
    const std::string name = opt.Get("--name", "model");
    const int level = opt.Int("--level", 8);
    const int runs = std::max(1, opt.Int("--runs", 3));
    const double tolerance = opt.Real("--tolerance", 0.02);
    const bool process = !opt.Has("--no-process");
    const bool trimHeap = opt.Has("--trim-heap");
    const std::string csv = opt.Get("--csv", "-");
    const std::string work = opt.Get("--work", "/tmp/gsbench");
    const std::string meshlabserver = opt.Get("--meshlabserver", "");
    const double targetPercent = opt.Real("--target-percent", 0);
    const double maxError = opt.Real("--max-error", 0);
    const std::vector<std::string> methods =
        Split(opt.Get("--methods", "ours,ours-circular,cgal-hierarchy,cgal-grid,meshlab-poisson,floor"));
    std::vector<int> threadCounts;
    for (const std::string &t : Split(opt.Get("--threads", "1,2"))) threadCounts.push_back(std::stoi(t));
    const std::uint32_t seedSalt = SeedSalt(opt);
    opt.RejectUnused();
    if (threadCounts.empty()) throw std::invalid_argument("--threads needs at least one count");
    if (!(targetPercent >= 0 && targetPercent <= 100)) throw std::invalid_argument("--target-percent must be in (0, 100]");
    if (!(maxError >= 0 && maxError < 1)) throw std::invalid_argument("--max-error must be in (0, 1)");
    auto wanted = [&](const std::string &m) { return std::find(methods.begin(), methods.end(), m) != methods.end(); };
    if (wanted("meshlab-poisson") && meshlabserver.empty())
        throw std::invalid_argument("meshlab-poisson needs --meshlabserver");
    mkdir(work.c_str(), 0755);
    const std::string self = SelfExecutable();
    const std::string log = work + "/" + name + ".log";
    // Runs with a target or a bound get their own output names (the files are kept for viewing).
    std::string variant = "_n" + std::to_string(level);
    if (targetPercent > 0) variant += "_t" + Number(targetPercent);
    if (maxError > 0) variant += "_e" + Number(maxError);
    if (seedSalt != 0) variant += "_s" + std::to_string(seedSalt);
    auto outputPath = [&](const std::string &method) { return work + "/" + name + variant + "_" + method + ".ply"; };

    PointMesh input;
    LoadPointSet(inputPath, input);
    OursConfig config;
    config.level = level;
    config.maxError = maxError;
    config.seedSalt = seedSalt;
    if (targetPercent > 0) config.targetCount = std::max(1, int(std::lround(targetPercent / 100.0 * input.vn)));
    // The arguments that make `gsbench run ours` do the same as the in-process runs.
    std::vector<std::string> oursArguments = {"--level", std::to_string(level)};
    if (config.targetCount > 0) oursArguments.insert(oursArguments.end(), {"--target-count", std::to_string(config.targetCount)});
    if (maxError > 0) oursArguments.insert(oursArguments.end(), {"--max-error", Number(maxError, 17)});
    if (config.seedSalt != 0) oursArguments.insert(oursArguments.end(), {"--seed-salt", std::to_string(config.seedSalt)});
    const double diagonal = input.bbox.Diag();
    // The metric and the searches use every core; only the timed runs pin the thread count.
    const int cores = omp_get_num_procs();
    std::fprintf(stderr, "%s: %d points, level %d\n", name.c_str(), input.vn, level);

    std::vector<Row> rows;
    auto newRow = [&](const std::string &method) {
        Row r;
        r.model = name;
        r.method = method;
        r.inputPoints = input.vn;
        r.level = level;
        r.targetPercent = targetPercent;
        r.targetPoints = config.targetCount;
        r.maxError = maxError;
        return r;
    };
    auto measure = [&](Row &r, const SimplifiedSet &set) {
        omp_set_num_threads(cores);
        std::vector<float> distance;
        r.error = Evaluate(input, set, maxError > 0 ? &distance : nullptr);
        r.measured = true;
        r.points = set.Count();
        if (maxError > 0) {
            // D* > E per point, over the points the metric measured (the distance is not NaN).
            const double limit = maxError * r.error.diagonal;
            size_t above = 0, defined = 0;
            for (float d : distance) {
                if (std::isnan(d)) continue;
                ++defined;
                above += d > limit;
            }
            r.dstarAboveFraction = defined ? double(above) / defined : kNaN;
        }
    };
    // Rows are announced at the end, once the interleaved timings are in.
    auto finish = [&](Row &r) {
        rows.push_back(r);
        return rows.size() - 1;
    };
    InterleavedTimings timings;

    // Ours fixes the count every peer is matched to.
    SimplifiedSet ours;
    {
        vcg::gaussphere::IndexArray reference; // representative[] of the first thread count, to check the others
        vcg::gaussphere::metric::SurfelErrorStats error;
        double errorAboveFraction = kNaN;
        // Without an "ours" row, one untimed run is enough to fix the target.
        if (!wanted("ours")) threadCounts.resize(1);
        for (int threads : threadCounts) {
            vcg::gaussphere::ResamplingResult result;
            Row r = newRow("ours");
            r.threads = threads;
            r.parameters = "n=" + std::to_string(level);
            if (config.targetCount > 0) r.parameters += " target=" + std::to_string(config.targetCount);
            if (maxError > 0) r.parameters += " max_error=" + Number(maxError);
            result = RunOurs(input, config, threads, nullptr); // the output; timed in the rounds below
            r.levelUsed = result.stats.levelUsed;
            r.splitsForErrorBound = result.stats.splitsForErrorBound;
            r.splitsForSurfaceBound = result.stats.splitsForSurfaceBound;
            r.pointsAboveBound = result.stats.pointsAboveErrorBound;
            r.splitsForTarget = result.stats.splitsForTarget;
            r.mergesForTarget = result.stats.mergesForTarget;
            r.ownPlaneMax = MaxOwnPlaneDistance(input, result);
            if (reference.empty() || result.representative != reference) {
                if (!reference.empty())
                    std::fprintf(stderr, "  warning: ours with %d threads differs from %d threads\n", threads,
                                 threadCounts.front());
                ToSimplifiedSet(result, ours);
                measure(r, ours);
                error = r.error;
                errorAboveFraction = r.dstarAboveFraction;
                if (reference.empty()) reference = result.representative;
            } else {
                r.error = error; // identical output: identical figures
                r.dstarAboveFraction = errorAboveFraction;
                r.measured = true;
                r.points = ours.Count();
            }
            if (process && wanted("ours")) {
                const ProcessFigures f = MeasureProcess(runs, [&]() {
                    std::vector<std::string> args = {self, "run", "ours", inputPath, outputPath("ours"), "--threads",
                                                     std::to_string(threads)};
                    args.insert(args.end(), oursArguments.begin(), oursArguments.end());
                    return RunChild(args, log);
                });
                r.timeProcess = f.seconds;
                r.peakMegabytes = f.peakMegabytes;
            }
            if (wanted("ours")) {
                const size_t index = finish(r);
                timings.Add(index, [&input, &rows, index, config, threads]() {
                    double s = 0;
                    rows[index].reducedThreadRuns += RunOurs(input, config, threads, &s).stats.threadsUsed < threads;
                    return s;
                });
            }
        }
    }
    const int target = ours.Count();

    if (wanted("ours-circular")) {
        Row r = newRow("ours-circular");
        r.parameters = "n=" + std::to_string(level);
        SimplifiedSet circular;
        vcg::tri::Append<PointMesh, PointMesh>::MeshCopy(circular.mesh, ours.mesh);
        for (auto &v : circular.mesh.vert) v.R() = 0;
        measure(r, circular);
        finish(r);
    }

    // The CGAL peers: match, time the algorithm at the matched parameter, measure, run as a process.
    std::unique_ptr<const CgalPointSet> cgalPoints; // outlives the block: the timed rounds run at the end
    if (wanted("cgal-hierarchy") || wanted("cgal-hierarchy-var") || wanted("cgal-grid")) {
        cgalPoints.reset(new CgalPointSet(input));
        const CgalPointSet &cgal = *cgalPoints;
        struct CgalPeer
        {
            std::string method, parameters;
            CountMatch match;
            std::function<std::vector<int>(double *)> run;
            std::vector<std::string> processArguments;
        };
        std::vector<CgalPeer> peers;
        if (wanted("cgal-hierarchy")) {
            const HierarchyMatch m = MatchHierarchy(cgal, target, tolerance);
            peers.push_back({"cgal-hierarchy", m.param.ToString(), m.match,
                             [points = &cgal, m](double *s) { return points->Hierarchy(m.param, s); },
                             {"--size", std::to_string(m.param.maxClusterSize), "--variation",
                              Number(m.param.maxVariation, 17)}});
        }
        if (wanted("cgal-hierarchy-var")) {
            // Variation-driven: clusters may grow to 4x the mean size where the surface is flat,
            // so the split budget goes to curved regions.
            const int cap = int(std::ceil(4.0 * input.vn / target));
            const HierarchyMatch m = MatchHierarchyVariation(cgal, cap, target, tolerance);
            peers.push_back({"cgal-hierarchy-var", m.param.ToString(), m.match,
                             [points = &cgal, m](double *s) { return points->Hierarchy(m.param, s); },
                             {"--size", std::to_string(m.param.maxClusterSize), "--variation",
                              Number(m.param.maxVariation, 17)}});
        }
        if (wanted("cgal-grid")) {
            const CountMatch m = MatchGrid(cgal, diagonal, target, tolerance);
            peers.push_back({"cgal-grid", GridParameters(m, diagonal), m,
                             [points = &cgal, m](double *s) { return points->Grid(m.parameter, s); },
                             {"--cell", Number(m.parameter, 17)}});
        }
        for (const CgalPeer &peer : peers) {
            Row r = newRow(peer.method);
            r.threads = 1;
            r.parameters = peer.parameters;
            r.matched = peer.match.withinTolerance;
            r.evaluations = peer.match.evaluations;
            const std::vector<int> kept = peer.run(nullptr); // the output; timed in the rounds below
            SimplifiedSet set;
            CopySubset(input, kept, set.mesh);
            measure(r, set);
            if (process) {
                std::vector<std::string> args = {self, "run", peer.method, inputPath, outputPath(peer.method)};
                args.insert(args.end(), peer.processArguments.begin(), peer.processArguments.end());
                const ProcessFigures f = MeasureProcess(runs, [&]() { return RunChild(args, log); });
                r.timeProcess = f.seconds;
                r.peakMegabytes = f.peakMegabytes;
            }
            timings.Add(finish(r), [run = peer.run]() {
                double s = 0;
                run(&s);
                return s;
            });
            if (!peer.match.withinTolerance && wanted("ours") && set.Count() > 0) {
                // The peer cannot reach our count (CGAL's hierarchy has no output between ~42 %
                // and ~58 % of the input): compare at its count instead, ours exact by TargetCount
                // (without an error bound, which could need more surfels than the count).
                OursConfig atPeer = config;
                atPeer.targetCount = set.Count();
                atPeer.maxError = 0;
                const vcg::gaussphere::ResamplingResult result = RunOurs(input, atPeer, threadCounts.front(), nullptr);
                Row o = newRow("ours@" + peer.method);
                o.threads = threadCounts.front();
                o.parameters = "n=" + std::to_string(level) + " target=" + std::to_string(atPeer.targetCount);
                o.targetPoints = atPeer.targetCount;
                o.levelUsed = result.stats.levelUsed;
                o.splitsForTarget = result.stats.splitsForTarget;
                o.mergesForTarget = result.stats.mergesForTarget;
                SimplifiedSet atPeerSet;
                ToSimplifiedSet(result, atPeerSet);
                measure(o, atPeerSet);
                finish(o);
            }
        }
    }

    if (wanted("meshlab-poisson")) {
        const MeshLabPoisson poisson(meshlabserver, inputPath, diagonal, work);
        const CountMatch m = poisson.Match(target, tolerance);
        Row r = newRow("meshlab-poisson");
        r.parameters = PoissonParameters(m, diagonal);
        r.matched = m.withinTolerance;
        r.evaluations = m.evaluations;
        const std::string output = outputPath("meshlab-poisson");
        // Even with --no-process one run is needed, for the output to measure.
        const ProcessFigures f = MeasureProcess(process ? runs : 1, [&]() { return poisson.Run(m.parameter, output); });
        if (process) {
            r.timeProcess = f.seconds;
            r.peakMegabytes = f.peakMegabytes;
        }
        SimplifiedSet set;
        LoadPointSet(output, set.mesh);
        measure(r, set);
        finish(r);
    }

    if (wanted("floor")) {
        Row r = newRow("floor");
        r.parameters = "S'=S";
        SimplifiedSet set;
        MakeIdentitySet(input, set);
        measure(r, set);
        finish(r);
    }

    for (const auto &timed : timings.Run(runs, trimHeap)) rows[timed.first].timeAlg = timed.second;
    for (const Row &r : rows) Announce(r);
    WriteRows(csv, rows);
    return 0;
}

// ---------------------------------------------------------------------------------------------
// run: one method as a whole process

int RunOne(const std::string &method, const std::string &inputPath, const std::string &outputPath, const Options &opt)
{
    const int level = opt.Int("--level", 8);
    const int threads = opt.Int("--threads", 1);
    HierarchyParams hierarchy;
    hierarchy.maxClusterSize = opt.Int("--size", hierarchy.maxClusterSize);
    hierarchy.maxVariation = opt.Real("--variation", hierarchy.maxVariation);
    const double cell = opt.Real("--cell", 0);
    OursConfig config;
    config.level = level;
    config.targetCount = opt.Int("--target-count", 0);
    config.maxError = opt.Real("--max-error", 0);
    config.seedSalt = SeedSalt(opt);
    opt.RejectUnused();

    PointMesh input, output;
    LoadPointSet(inputPath, input);
    if (method == "ours") {
        const auto result = RunOurs(input, config, threads, nullptr);
        vcg::gaussphere::WriteSurfels(result.surfels, output);
        SavePointSet(output, outputPath, true);
        return 0;
    }
    std::vector<int> kept;
    if (method == "cgal-hierarchy" || method == "cgal-hierarchy-var") {
        kept = CgalPointSet(input).Hierarchy(hierarchy);
    } else if (method == "cgal-grid") {
        if (!(cell > 0)) throw std::invalid_argument("cgal-grid needs --cell");
        kept = CgalPointSet(input).Grid(cell);
    } else {
        throw std::invalid_argument("unknown method " + method);
    }
    CopySubset(input, kept, output);
    SavePointSet(output, outputPath, false);
    return 0;
}

// ---------------------------------------------------------------------------------------------
// export: the matched peers' point sets as files

/// One peer's output matched to the requested count, as `export` reports it.
struct ExportedPeer
{
    std::string method, parameters;
    CountMatch match;
    int points = 0;
};

int Export(const std::string &inputPath, const Options &opt)
{
    const int target = opt.Int("--count", 0);
    const std::string prefix = opt.Get("--out", "");
    const std::vector<std::string> methods = Split(opt.Get("--methods", "cgal-hierarchy,cgal-grid,meshlab-poisson"));
    const std::string meshlabserver = opt.Get("--meshlabserver", "");
    const std::string work = opt.Get("--work", "/tmp/gsbench");
    const double tolerance = opt.Real("--tolerance", 0.02);
    const std::string csv = opt.Get("--csv", "-");
    opt.RejectUnused();
    if (target <= 0) throw std::invalid_argument("export needs --count N > 0");
    if (prefix.empty()) throw std::invalid_argument("export needs --out PREFIX");
    mkdir(work.c_str(), 0755);

    PointMesh input;
    LoadPointSet(inputPath, input);
    const double diagonal = input.bbox.Diag();
    std::unique_ptr<const CgalPointSet> cgal;
    auto cgalPoints = [&]() -> const CgalPointSet & {
        if (!cgal) cgal.reset(new CgalPointSet(input));
        return *cgal;
    };
    auto saveSubset = [&](const std::vector<int> &kept, const std::string &path) {
        PointMesh output;
        CopySubset(input, kept, output);
        SavePointSet(output, path, false);
        return output.vn;
    };

    std::vector<ExportedPeer> exported;
    for (const std::string &method : methods) {
        const std::string path = prefix + "_" + method + ".ply";
        ExportedPeer e;
        e.method = method;
        if (method == "cgal-hierarchy") {
            const HierarchyMatch m = MatchHierarchy(cgalPoints(), target, tolerance);
            e.parameters = m.param.ToString();
            e.match = m.match;
            e.points = saveSubset(cgalPoints().Hierarchy(m.param), path);
        } else if (method == "cgal-grid") {
            e.match = MatchGrid(cgalPoints(), diagonal, target, tolerance);
            e.parameters = GridParameters(e.match, diagonal);
            e.points = saveSubset(cgalPoints().Grid(e.match.parameter), path);
        } else if (method == "meshlab-poisson") {
            if (meshlabserver.empty()) throw std::invalid_argument("meshlab-poisson needs --meshlabserver");
            const MeshLabPoisson poisson(meshlabserver, inputPath, diagonal, work);
            e.match = poisson.Match(target, tolerance);
            e.parameters = PoissonParameters(e.match, diagonal);
            poisson.Run(e.match.parameter, path);
            e.points = PlyVertexCount(path);
        } else {
            throw std::invalid_argument("export: unknown method " + method);
        }
        std::fprintf(stderr, "  %-16s %8d pts (target %d) %s%s -> %s\n", method.c_str(), e.points, target,
                     e.parameters.c_str(), e.match.withinTolerance ? "" : ", NOT matched", path.c_str());
        exported.push_back(e);
    }

    std::ostringstream rows;
    for (const ExportedPeer &e : exported)
        rows << e.method << ',' << e.points << ',' << target << ',' << e.parameters << ','
             << (e.match.withinTolerance ? "yes" : "no") << ',' << e.match.evaluations << '\n';
    const char *header = "method,points,target,parameters,matched,match_evaluations\n";
    if (csv.empty() || csv == "-") {
        std::printf("%s%s", header, rows.str().c_str());
        return 0;
    }
    struct stat st;
    const bool fresh = stat(csv.c_str(), &st) != 0 || st.st_size == 0;
    std::ofstream out(csv, std::ios::app);
    if (fresh) out << header;
    out << rows.str();
    if (!out) throw std::runtime_error("cannot write " + csv);
    return 0;
}

int Neighbors(const std::string &inputPath, const Options &opt)
{
    const int k = opt.Int("--k", 16);
    const int threads = opt.Int("--threads", 2);
    const int runs = opt.Int("--runs", 5);
    opt.RejectUnused();
    if (k < 1 || threads < 1 || runs < 1) throw std::invalid_argument("--k, --threads and --runs must be positive");
    PointMesh input;
    LoadPointSet(inputPath, input);
    omp_set_num_threads(threads);
    std::vector<double> seconds;
    for (int r = 0; r < runs; ++r) seconds.push_back(TimeNanoflannNeighbors(input, k));
    std::printf("%.4f\n", Median(seconds));
    return 0;
}

int Usage(const char *program)
{
    std::fprintf(stderr,
                 "usage: %s compare INPUT.ply --name NAME [--level N] [--methods LIST] [--threads LIST]\n"
                 "                  [--runs R] [--csv OUT.csv] [--work DIR] [--meshlabserver PATH]\n"
                 "                  [--tolerance F] [--no-process] [--trim-heap] [--target-percent P] [--max-error E]\n"
                 "                  [--seed-salt S]\n"
                 "       %s run METHOD INPUT.ply OUTPUT.ply [--level N] [--threads T] [--size S]\n"
                 "                  [--variation V] [--cell C] [--target-count C] [--max-error E] [--seed-salt S]\n"
                 "       %s export INPUT.ply --count N --out PREFIX [--methods LIST] [--meshlabserver PATH]\n"
                 "                  [--work DIR] [--tolerance F] [--csv OUT.csv]\n"
                 "       %s knn INPUT.ply [--k K] [--threads T] [--runs R]\n"
                 "(see the comment at the top of bench/src/main.cpp)\n",
                 program, program, program, program);
    return 2;
}

} // namespace

int main(int argc, char **argv)
{
    try {
        const std::string command = argc > 1 ? argv[1] : "";
        if (command == "compare" && argc >= 3) return Compare(argv[2], Options(argc, argv, 3));
        if (command == "run" && argc >= 5) return RunOne(argv[2], argv[3], argv[4], Options(argc, argv, 5));
        if (command == "export" && argc >= 3) return Export(argv[2], Options(argc, argv, 3));
        if (command == "knn" && argc >= 3) return Neighbors(argv[2], Options(argc, argv, 3));
        return Usage(argv[0]);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "gsbench: %s\n", e.what());
        return 1;
    }
}
