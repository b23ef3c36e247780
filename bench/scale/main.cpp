// gsscale: how the Gaussian sphere resampler scales to millions of points.
//
//   gsscale generate --points N [--shape S] [--seed S] [--noise X] --out FILE.ply
//       writes a generated point set (binary PLY, float x y z nx ny nz)
//   gsscale run --points N [--shape S] [--seed S] [--noise X] [--level L] [--target-percent P] [--trace 1]
//       generates in memory, resamples once, prints key=value lines (one measurement)
//   gsscale bench [--sizes 1000000,5000000,20000000] [--threads 2,1] [--shape S] ...
//                 --csv FILE --md FILE [--commit TEXT]
//       runs `run` in a fresh child process per (size, thread count) and writes the tables
//   gsscale probe-neighbours --points N [--shape S] ...
//       diagnostic: how many points the neighbour grid hands to its kd-tree fallback
//
// Shapes: "drilled-box" (analytic, sharp edges) or a model NAME of --data-dir (default: the
// shared data folder), densified from NAME_mesh.ply. Default: dragon. Generator options:
// --order random|morton, --noise SIGMA, --coincident M, --outlier D (point_generator.h).
//
// What one measurement reports (see process_probe.h for how peaks are taken):
// - stage times (ResamplingStats), total wall and CPU time, per point;
// - the input layer: RSS after generation, before resampling; memory beyond the input:
//   peak RSS during resampling minus that, per input point, overall and per stage
//   (the stages are the intervals between progress callbacks);
// - the longest interval between two progress callbacks (responsiveness).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <omp.h>

#include <vcg_ext/gaussphere/oriented_point_mesh.h>
#include <vcg_ext/gaussphere/resampling.h>

#include "point_generator.h"
#include "process_probe.h"

using namespace vcg::gaussphere;

namespace gsscale {
namespace {

typedef std::map<std::string, std::string> Options;
typedef std::chrono::steady_clock Clock;

Options ParseOptions(int argc, char **argv, int first)
{
    Options o;
    for (int a = first; a < argc; ++a) {
        const std::string key = argv[a];
        if (key.compare(0, 2, "--") != 0 || a + 1 >= argc) throw std::runtime_error("expected --option value at " + key);
        o[key.substr(2)] = argv[++a];
    }
    return o;
}

std::string Get(const Options &o, const std::string &key, const std::string &fallback)
{
    const auto it = o.find(key);
    return it == o.end() ? fallback : it->second;
}

GeneratorParams GeneratorFrom(const Options &o)
{
    GeneratorParams g;
    g.shape = Get(o, "shape", g.shape);
    g.dataDir = Get(o, "data-dir", GSSCALE_DATA_DIR);
    g.count = std::stoll(Get(o, "points", "1000000"));
    g.seed = std::stoull(Get(o, "seed", "1"));
    g.noise = std::stod(Get(o, "noise", "0"));
    g.order = Get(o, "order", g.order);
    g.coincident = std::stoll(Get(o, "coincident", "0"));
    g.outlier = std::stod(Get(o, "outlier", "0"));
    return g;
}

std::vector<long long> ParseList(const std::string &text)
{
    std::vector<long long> values;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) values.push_back(std::stoll(item));
    return values;
}

// ---------------------------------------------------------------------------------------
// One measurement.

/// The stages as the resampler announces them through its callback. Each progress call
/// closes the interval opened by the previous one: the time and the memory peak between
/// two calls belong to the stage the first of them named.
struct CallbackEvent
{
    Clock::time_point time;
    int percent;
    std::string label;
    std::size_t peakBefore; ///< peak RSS of the interval that this call closes
    std::size_t resident, heapInUse; ///< RSS and live heap blocks at the call
};

struct CallbackRecorder
{
    bool peakResettable = false;
    std::vector<CallbackEvent> events;

    void Record(int percent, const char *label)
    {
        const Clock::time_point now = Clock::now(); // before the probes: they are not the resampler's time
        events.push_back({now, percent, label ? label : "", PeakResidentBytes(), ResidentBytes(), HeapInUseBytes()});
        ResetPeakResident();
    }
};

CallbackRecorder *gRecorder = nullptr; // vcg::CallBackPos is a plain function pointer

bool RecordProgress(const int percent, const char *label)
{
    gRecorder->Record(percent, label);
    return true;
}

/// "Gaussian sphere resampling: neighbour search" -> "neighbour search"
std::string ShortStage(const std::string &label)
{
    const size_t colon = label.find(": ");
    return colon == std::string::npos ? label : label.substr(colon + 2);
}

int RunOnce(const Options &o)
{
    const GeneratorParams gen = GeneratorFrom(o);
    ResamplingParams param; // defaults: level 8
    param.subdivisionLevel = std::stoi(Get(o, "level", std::to_string(param.subdivisionLevel)));
    // A target size (0: off) runs the level search and the exchanges (max_error_exchange.h) too.
    const double targetPercent = std::stod(Get(o, "target-percent", "0"));
    param.targetCount = int(std::lround(targetPercent / 100 * double(gen.count)));

    if (Get(o, "allocator", "mmap") == "mmap") UseMmapForLargeBlocks();
    const std::size_t rssStart = ResidentBytes();
    const Clock::time_point genStart = Clock::now();
    OrientedPointMesh mesh;
    GeneratePoints(gen, mesh);
    const double generateSeconds = std::chrono::duration<double>(Clock::now() - genStart).count();
    TrimHeap(); // the source mesh is gone; give its pages back so the baseline is the points alone
    const std::size_t rssInput = ResidentBytes();
    const std::size_t heapInput = HeapInUseBytes();

    CallbackRecorder recorder;
    gRecorder = &recorder;
    recorder.peakResettable = ResetPeakResident();
    const std::size_t peakBeforeCall = PeakResidentBytes(); // generation's own peak, if not resettable
    const double cpuStart = CpuSeconds();
    const Clock::time_point callStart = Clock::now();
    const ResamplingResult result = ResamplePointSet(mesh, param, RecordProgress);
    const Clock::time_point callEnd = Clock::now();
    const double cpuSeconds = CpuSeconds() - cpuStart;
    const std::size_t peakAfterLast = PeakResidentBytes();
    const ResamplingStats &s = result.stats;
    const double n = s.inputCount;

    auto out = [](const std::string &key, double value) { std::printf("%s=%.17g\n", key.c_str(), value); };
    std::printf("shape=%s\n", gen.shape.c_str());
    out("points", n);
    out("threads", omp_get_max_threads());
    out("threads_used", s.threadsUsed); // the OpenMP thread count of the run
    out("generate_s", generateSeconds);
    out("neighbours_s", s.secondsNeighbors);
    out("propagation_s", s.secondsPropagation);
    out("normalization_s", s.secondsNormalization);
    out("refinement_s", s.secondsRefinement);
    out("surfels_s", s.secondsSurfels);
    out("exchanges_s", s.secondsExchanges);
    out("total_s", std::chrono::duration<double>(callEnd - callStart).count());
    out("cpu_s", cpuSeconds);
    out("output", s.outputCount);
    out("naive", s.naiveCount);
    out("iterations", s.iterations);
    out("mean_neighbours", s.meanAdaptiveNeighbors);
    out("l21_rms", s.normalErrorRms);
    out("vertex_bytes", sizeof(OrientedPointMesh::VertexType));
    out("rss_start_bytes", rssStart);
    out("rss_input_bytes", rssInput);
    out("result_bytes", result.surfels.capacity() * sizeof(Surfel) + result.representative.capacity() * sizeof(int));
    out("peak_resettable", recorder.peakResettable);

    // Stage intervals: call -> first callback, callback i -> callback i+1, last -> return.
    std::size_t peak = peakAfterLast;
    double longestGap = 0;
    std::string longestStage;
    Clock::time_point previous = callStart;
    std::string stage = "before first callback";
    // A stage spans every interval its callbacks open (the exchanges report once per trial):
    // its peak is their largest, its time their sum.
    std::map<std::string, std::size_t> stagePeak;
    std::map<std::string, double> stageSeconds;
    auto closeInterval = [&](Clock::time_point end, std::size_t intervalPeak) {
        const double gap = std::chrono::duration<double>(end - previous).count();
        if (gap > longestGap) { longestGap = gap; longestStage = stage; }
        peak = std::max(peak, intervalPeak);
        std::string key = stage;
        std::replace(key.begin(), key.end(), ' ', '_');
        stagePeak[key] = std::max(stagePeak[key], intervalPeak);
        stageSeconds[key] += gap;
    };
    const bool trace = Get(o, "trace", "0") == "1";
    for (const CallbackEvent &e : recorder.events) {
        // --trace 1: each interval's length and peak, then the RSS and live heap blocks at its end
        // (B/point beyond the input), with its stage.
        if (trace)
            std::fprintf(stderr, "trace %7.3f s peak %6.1f rss %6.1f heap %6.1f B/pt  %s\n",
                         std::chrono::duration<double>(e.time - previous).count(),
                         (double(e.peakBefore) - double(rssInput)) / n, (double(e.resident) - double(rssInput)) / n,
                         (double(e.heapInUse) - double(heapInput)) / n, stage.c_str());
        closeInterval(e.time, e.peakBefore);
        previous = e.time;
        stage = ShortStage(e.label);
    }
    closeInterval(callEnd, peakAfterLast);
    for (const auto &s : stagePeak) {
        if (recorder.peakResettable) out("stage_peak_beyond_bytes." + s.first, double(s.second) - double(rssInput));
        out("stage_s." + s.first, stageSeconds[s.first]);
    }
    if (!recorder.peakResettable) peak = std::max(peak, peakBeforeCall); // includes generation: an upper bound
    out("callbacks", recorder.events.size());
    out("longest_callback_gap_s", longestGap);
    std::printf("longest_callback_gap_stage=%s\n", longestStage.c_str());
    out("peak_bytes", peak);
    out("beyond_input_bytes", double(peak) - double(rssInput));
    return 0;
}

/// Diagnostic: how many points the grid leaves to PointGrid's kd-tree fallback. The
/// fallback runs after every grid cell is done and first builds a kd-tree over all N
/// points (about 20 B/point); the sink samples RSS and notes the call after which it rose
/// by more than 8 B/point: the calls from there on are the kd-tree's answers.
int ProbeNeighbours(const Options &o)
{
    UseMmapForLargeBlocks();
    OrientedPointMesh mesh;
    GeneratePoints(GeneratorFrom(o), mesh);
    vcg::gaussphere::PointArray points;
    points.reserve(mesh.vert.size());
    for (const auto &v : mesh.vert) points.push_back(v.cP());
    const long long n = (long long)points.size();
    const PointGrid grid(points);
    const std::size_t before = ResidentBytes();
    long long calls = 0, callsAtRise = -1;
    grid.ForAllKNearest(16, [&](int, const int *, const float *, int) {
        long long call;
#pragma omp atomic capture
        call = calls++;
        // The tail is sampled at every call: the fallback may answer only a handful of points.
        if ((call % 64 == 0 || call >= n - 100000) && ResidentBytes() > before + 8 * std::size_t(n)) {
#pragma omp critical
            if (callsAtRise < 0 || call < callsAtRise) callsAtRise = call;
        }
    });
    std::printf("points=%lld cells=%d points_per_cell=%.2f kdtree_answers=%lld\n", n, grid.CellCount(),
                double(n) / grid.CellCount(), callsAtRise < 0 ? 0 : n - callsAtRise);
    return 0;
}

int Generate(const Options &o)
{
    const GeneratorParams gen = GeneratorFrom(o);
    const std::string path = Get(o, "out", "");
    if (path.empty()) throw std::runtime_error("generate needs --out FILE.ply");
    OrientedPointMesh mesh;
    GeneratePoints(gen, mesh);
    WriteOrientedPly(mesh, path);
    std::printf("wrote %d points to %s\n", mesh.vn, path.c_str());
    return 0;
}

// ---------------------------------------------------------------------------------------
// The benchmark: one child process per measurement, then the tables.

struct Measurement
{
    std::map<std::string, std::string> values;
    std::string loadBefore;

    double Num(const std::string &key) const
    {
        const auto it = values.find(key);
        return it == values.end() ? std::nan("") : std::atof(it->second.c_str());
    }
    std::string Text(const std::string &key) const
    {
        const auto it = values.find(key);
        return it == values.end() ? "" : it->second;
    }
    double PerPoint(const std::string &key) const { return Num(key) / Num("points"); }
};

Measurement ParseMeasurement(const std::string &text)
{
    Measurement m;
    std::stringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        const size_t eq = line.find('=');
        if (eq != std::string::npos) m.values[line.substr(0, eq)] = line.substr(eq + 1);
    }
    return m;
}

std::string Format(const char *format, double value)
{
    if (std::isnan(value)) return "n/a";
    char text[64];
    std::snprintf(text, sizeof(text), format, value);
    return text;
}

const double kMiB = 1024.0 * 1024.0;
const char *kStages[] = {"reading points", "neighbour search", "clustering", "surfels"};

/// Memory the code review attributes to each live buffer, in bytes per input point, for
/// k neighbour slots and c = clusters / points; 'when' lists the stages that hold it.
/// The figures follow the declarations in vcg_ext/gaussphere (see README.md here).
struct LedgerRow { const char *buffer; const char *where; double perPoint, perCluster; const char *when; };
const LedgerRow kLedger[] = {
    {"result.representative (int)", "resampling.h", 4, 0, "RNCS"},
    {"points copy (Point3f)", "resampling.h", 12, 0, "RNCS"},
    {"normals copy (Point3f)", "resampling.h", 12, 0, "RNCS"},
    {"source index (int)", "resampling.h", 4, 0, "RNCS"},
    {"grid sort keys (uint64,int) + radix scratch: freed before the graph exists", "point_grid.h", 32, 0, "-"},
    {"grid order_ (int)", "point_grid.h", 4, 0, "N"},
    {"grid cell start/key/hash (~8 points per cell; a dense cell array only below 2^21 cells)", "point_grid.h", 4, 0, "N"},
    {"graph adjacency (k ints)", "adaptive_neighbors.h", -1, 0, "NCS"},
    {"graph count, found (uint8)", "adaptive_neighbors.h", 2, 0, "NCS"},
    {"graph spacing (float)", "adaptive_neighbors.h", 4, 0, "NCS"},
    {"FillUnknownSpacing copy (float), transient", "adaptive_neighbors.h", 4, 0, "n"},
    // Built by ForAllKNearest over all N points when more than 64 points are unresolved
    // (fewer are answered by a scan); gone before FillUnknownSpacing runs, so it replaces
    // that term at the stage's peak.
    {"kd-tree fallback (nanoflann): index 4 + nodes ~18 (measured 21.9 on a 1M-point sphere)", "point_grid.h", 22, 0, "k"},
    {"crease flag per point (char)", "crease_points.h", 1, 0, "CS"},
    {"Gaussian triangle per point (int)", "resampling.h", 4, 0, "C"},
    {"cluster label (int)", "clustering.h", 4, 0, "CS"},
    {"ClusterMembers index (int) + offsets", "clustering.h", 4, 8, "cs"},
    {"split planes: plane index (int) per cluster; centroid + axis (48 B) only per cluster split", "cluster_normalization.h", 0, 4, "c"},
    {"surfels (sizeof(Surfel) each, result)", "surfel_generation.h", 0, double(sizeof(vcg::gaussphere::Surfel)), "S"},
    {"offset fit: blend weight 20 B + offset 4 B per surfel, transient", "surfel_offset.h", 0, 24, "s"},
};

/// Expected peak beyond the input in stage s ('R','N','C','S'): the buffers held
/// throughout (capital letter) plus the transient ones of that stage (small letter), which
/// coexist at the stage's peak ('-': never live at a peak). With kdTree, the neighbour
/// stage's peak is the kd-tree fallback's ('k') instead of the spacing copy ('n').
double LedgerPeak(char stage, int k, double clustersPerPoint, bool kdTree = false)
{
    double sum = 0;
    for (const LedgerRow &r : kLedger) {
        const std::string when = r.when;
        bool live = when.find(stage) != std::string::npos || when.find(char(stage + 32)) != std::string::npos;
        if (stage == 'N' && kdTree) live = (live && when != "n") || when == "k";
        if (live) sum += (r.perPoint < 0 ? 4.0 * k : r.perPoint) + r.perCluster * clustersPerPoint;
    }
    return sum;
}

void WriteCsv(const std::vector<Measurement> &runs, const std::string &path)
{
    std::vector<std::string> keys;
    for (const Measurement &m : runs)
        for (const auto &kv : m.values)
            if (std::find(keys.begin(), keys.end(), kv.first) == keys.end()) keys.push_back(kv.first);
    std::ofstream csv(path);
    csv << "load_before";
    for (const std::string &k : keys) csv << ',' << k;
    csv << '\n';
    for (const Measurement &m : runs) {
        csv << '"' << m.loadBefore << '"';
        for (const std::string &k : keys) csv << ',' << m.Text(k);
        csv << '\n';
    }
    if (!csv) throw std::runtime_error("cannot write " + path);
}

void WriteMarkdown(const std::vector<Measurement> &runs, const Options &o, const std::string &loadStart,
                   const std::string &loadEnd, const std::string &path)
{
    std::ofstream md(path);
    const double target = 150;
    md << "# Scaling of the Gaussian sphere resampler\n\n"
       << "Written by `scripts/bench_scale.sh` (program: `bench/scale/main.cpp`); analysis and "
          "recommendations: [README.md](README.md).\n\n"
       << "- input: " << Get(o, "shape", "dragon") << " densified (seed " << Get(o, "seed", "1") << ", noise "
       << Get(o, "noise", "0") << ", point order " << Get(o, "order", "random")
       << "), generated in memory; "
       << (Get(o, "target-percent", "0") != "0"
               ? "TargetPercentage " + Get(o, "target-percent", "0") +
                     " (exact count from level 8: level search, merges or splits, exchanges for the largest error; k = 16)\n"
               : std::string("default parameters (level 8, k = 16)\n"))
       << "- commit: " << Get(o, "commit", "unknown") << "\n"
       << "- machine: " << MachineDescription() << "\n"
       << "- load average (1/5/15 min) at start: " << loadStart << ", at end: " << loadEnd
       << " (shared machine: wall times include other jobs' interference; CPU time and memory do not depend on "
          "the load as much; \"cores used\" = CPU time / wall time shows whether the second core was free)\n"
       << "- one run per row, each in a fresh process; memory beyond the input = peak RSS during "
          "`ResamplePointSet` minus the RSS after generation (the input mesh, "
       << (runs.empty() ? 0 : int(runs[0].Num("vertex_bytes"))) << " B per vertex)\n\n";

    md << "## Time and memory\n\n"
       << "| points | threads | total s | ns/pt (wall) | CPU s | ns/pt (CPU) | cores used | neighbours s | propagation s | "
          "normalization s | surfels s | output | output % | input MiB | peak MiB | beyond input MiB | "
          "B/pt beyond input | load before |\n"
       << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const Measurement &m : runs)
        md << "| " << Format("%.0f", m.Num("points")) << " | " << m.Text("threads") << " | "
           << Format("%.2f", m.Num("total_s")) << " | " << Format("%.0f", 1e9 * m.PerPoint("total_s")) << " | "
           << Format("%.2f", m.Num("cpu_s")) << " | " << Format("%.0f", 1e9 * m.PerPoint("cpu_s")) << " | "
           << Format("%.2f", m.Num("cpu_s") / m.Num("total_s")) << " | " << Format("%.2f", m.Num("neighbours_s")) << " | " << Format("%.2f", m.Num("propagation_s")) << " | "
           << Format("%.2f", m.Num("normalization_s")) << " | " << Format("%.2f", m.Num("surfels_s")) << " | "
           << Format("%.0f", m.Num("output")) << " | " << Format("%.1f", 100 * m.PerPoint("output")) << " | "
           << Format("%.0f", m.Num("rss_input_bytes") / kMiB) << " | " << Format("%.0f", m.Num("peak_bytes") / kMiB)
           << " | " << Format("%.0f", m.Num("beyond_input_bytes") / kMiB) << " | "
           << Format("%.1f", m.PerPoint("beyond_input_bytes")) << " | " << m.loadBefore << " |\n";

    md << "\n## Speed-up, 1 to 2 threads\n\n| points | wall 1 thread s | wall 2 threads s | speed-up |\n|---:|---:|---:|---:|\n";
    std::map<long long, std::map<int, double>> wall;
    for (const Measurement &m : runs) wall[(long long)m.Num("points")][int(m.Num("threads"))] = m.Num("total_s");
    for (const auto &bySize : wall) {
        const auto one = bySize.second.find(1), two = bySize.second.find(2);
        if (one == bySize.second.end() || two == bySize.second.end()) continue;
        md << "| " << bySize.first << " | " << Format("%.2f", one->second) << " | " << Format("%.2f", two->second)
           << " | " << Format("%.2f", one->second / two->second) << " |\n";
    }

    md << "\n## Memory beyond the input by stage (bytes per input point)\n\n"
       << "Measured: the peak RSS within each interval between progress callbacks (the kernel's high-water "
          "mark, reset at every callback), minus the input. Expected: the sum of the buffers live in that "
          "stage according to the code (ledger below), with c = output / points for the per-cluster terms.\n\n"
       << "| points | threads |";
    for (const char *stage : kStages) md << ' ' << stage << " |";
    md << " expected: reading | neighbours | clustering | surfels |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Measurement &m : runs) {
        md << "| " << Format("%.0f", m.Num("points")) << " | " << m.Text("threads") << " |";
        for (std::string stage : kStages) {
            std::replace(stage.begin(), stage.end(), ' ', '_');
            md << ' ' << Format("%.1f", m.PerPoint("stage_peak_beyond_bytes." + stage)) << " |";
        }
        const double c = m.PerPoint("output");
        for (char s : std::string("RNCS")) {
            md << ' ' << Format("%.1f", LedgerPeak(s, 16, c));
            if (s == 'N') md << " (" << Format("%.1f", LedgerPeak(s, 16, c, true)) << " with kd-tree)";
            md << " |";
        }
        md << '\n';
    }
    md << "\nLedger (k = 16; stages: R reading, N neighbour search, C clustering, S surfels; a small letter "
          "marks a buffer that lives only inside that stage):\n\n| buffer | file | B/point | B/cluster | stages |\n"
          "|---|---|---:|---:|---|\n";
    for (const LedgerRow &r : kLedger)
        md << "| " << r.buffer << " | " << r.where << " | " << (r.perPoint < 0 ? 64.0 : r.perPoint) << " | "
           << r.perCluster << " | " << r.when << " |\n";

    if (Get(o, "target-percent", "0") != "0") {
        md << "\n## Target size: the stages beyond the level path\n\n"
           << "Peaks: the largest over the intervals between callbacks that the stage's reports open (bytes per "
              "input point beyond the input).\n\n"
           << "| points | threads | output | merges or splits s | exchanges s | total s | B/pt beyond input | "
              "peak merging | peak exchanges |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Measurement &m : runs)
            md << "| " << Format("%.0f", m.Num("points")) << " | " << m.Text("threads") << " | "
               << Format("%.0f", m.Num("output")) << " | " << Format("%.2f", m.Num("refinement_s")) << " | "
               << Format("%.2f", m.Num("exchanges_s")) << " | " << Format("%.2f", m.Num("total_s")) << " | "
               << Format("%.1f", m.PerPoint("beyond_input_bytes")) << " | "
               << Format("%.1f", m.PerPoint("stage_peak_beyond_bytes.merging_clusters")) << " | "
               << Format("%.1f", m.PerPoint("stage_peak_beyond_bytes.exchanges_for_the_largest_error")) << " |\n";
    }

    md << "\n## Responsiveness: longest interval between progress callbacks\n\n"
       << "| points | threads | callbacks | longest gap s | in stage |\n|---:|---:|---:|---:|---|\n";
    for (const Measurement &m : runs)
        md << "| " << Format("%.0f", m.Num("points")) << " | " << m.Text("threads") << " | " << m.Text("callbacks")
           << " | " << Format("%.2f", m.Num("longest_callback_gap_s")) << " | " << m.Text("longest_callback_gap_stage")
           << " |\n";

    // Verdict, per thread count: the per-point figures of the largest size against the smallest.
    md << "\n## Linearity\n\n";
    std::map<int, std::vector<const Measurement *>> byThreads;
    for (const Measurement &m : runs) byThreads[int(m.Num("threads"))].push_back(&m);
    for (auto &t : byThreads) {
        auto &list = t.second;
        std::sort(list.begin(), list.end(), [](const Measurement *a, const Measurement *b) { return a->Num("points") < b->Num("points"); });
        if (list.size() < 2) continue;
        const Measurement &small = *list.front(), &large = *list.back();
        md << "- " << t.first << " thread(s), " << Format("%.0f", small.Num("points")) << " -> "
           << Format("%.0f", large.Num("points")) << " points: CPU ns/point x"
           << Format("%.2f", large.PerPoint("cpu_s") / small.PerPoint("cpu_s")) << ", wall ns/point x"
           << Format("%.2f", large.PerPoint("total_s") / small.PerPoint("total_s")) << ", bytes/point beyond input x"
           << Format("%.2f", large.PerPoint("beyond_input_bytes") / small.PerPoint("beyond_input_bytes")) << "\n";
    }
    double worst = 0;
    for (const Measurement &m : runs) worst = std::max(worst, m.PerPoint("beyond_input_bytes"));
    md << "- memory target <= " << target << " B/point beyond the input: "
       << (worst <= target ? "met" : "MISSED") << " (worst " << Format("%.1f", worst) << " B/point)\n";
    if (!md) throw std::runtime_error("cannot write " + path);
}

int Bench(const Options &o)
{
    const std::vector<long long> sizes = ParseList(Get(o, "sizes", "1000000,5000000,20000000"));
    const std::vector<long long> threads = ParseList(Get(o, "threads", "2,1"));
    const std::string csvPath = Get(o, "csv", ""), mdPath = Get(o, "md", "");
    if (csvPath.empty() || mdPath.empty()) throw std::runtime_error("bench needs --csv FILE and --md FILE");
    // The child gets the generator and resampler options unchanged.
    std::vector<std::string> passOn;
    for (const char *key : {"shape", "seed", "noise", "order", "coincident", "outlier", "level", "target-percent", "data-dir", "allocator"})
        if (o.count(key)) { passOn.push_back(std::string("--") + key); passOn.push_back(o.at(key)); }

    const std::string loadStart = LoadAverage();
    std::vector<Measurement> runs;
    for (long long size : sizes)
        for (long long t : threads) {
            std::vector<std::string> args = {"run", "--points", std::to_string(size)};
            args.insert(args.end(), passOn.begin(), passOn.end());
            const std::string load = LoadAverage();
            std::fprintf(stderr, "gsscale: %lld points, %lld thread(s), load %s ...\n", size, t, load.c_str());
            const ChildOutput child = RunSelf(args, {"OMP_NUM_THREADS=" + std::to_string(t)});
            if (child.exitStatus != 0) throw std::runtime_error("run failed with status " + std::to_string(child.exitStatus));
            Measurement m = ParseMeasurement(child.stdoutText);
            m.loadBefore = load;
            std::fprintf(stderr, "  %.2f s wall, %.2f s CPU, %.1f B/point beyond input, longest callback gap %.2f s\n",
                         m.Num("total_s"), m.Num("cpu_s"), m.PerPoint("beyond_input_bytes"), m.Num("longest_callback_gap_s"));
            runs.push_back(m);
            // Written after every run, so that an interrupted benchmark keeps what it measured.
            WriteCsv(runs, csvPath);
            WriteMarkdown(runs, o, loadStart, LoadAverage(), mdPath);
        }
    return 0;
}

} // namespace
} // namespace gsscale

int main(int argc, char **argv)
{
    const std::string command = argc > 1 ? argv[1] : "";
    try {
        const gsscale::Options o = gsscale::ParseOptions(argc, argv, 2);
        if (command == "run") return gsscale::RunOnce(o);
        if (command == "generate") return gsscale::Generate(o);
        if (command == "bench") return gsscale::Bench(o);
        if (command == "probe-neighbours") return gsscale::ProbeNeighbours(o);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "gsscale %s: %s\n", command.c_str(), e.what());
        return 1;
    }
    std::fprintf(stderr, "usage: %s generate|run|bench --option value ... (see bench/scale/main.cpp)\n", argv[0]);
    return 2;
}
