// splat_frames_bench: times the splat sizes of a raw point cloud (the distance to each point's
// k-th nearest neighbour, what the render plugin and splat_render compute for clouds without
// ellipses or radii): splat::nearestNeighbourRadii (the project's grid, parallel) against its
// peer, vcglib's kd-tree (built on one thread, as vcglib builds it, and queried in parallel), on
// the same points in the same run. Checks that both give the same radii.
//
//   splat_frames_bench [--points N] [--ply FILE] [--k K] [--repeat R]
// Without --ply: N points (default 5,000,000) on a bumpy sphere, uniformly random, with noise.
// Prints one CSV row per repetition: wall-clock and CPU seconds (all threads of the process) of
// each, their ratios (kd-tree / grid), and the points whose radii differ by more than 1e-5
// relative. On a machine shared with other work the CPU seconds divided by the thread count
// estimate the wall-clock time the machine would give alone.

#include "point_set_file.h"
#include "surfel_arrays.h"

#include <vcg/space/index/kdtree/kdtree.h>

#include <omp.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

struct Times
{
    double wall, cpu;
};

Times now()
{
    timespec cpu;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu);
    return {std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(),
            double(cpu.tv_sec) + 1e-9 * double(cpu.tv_nsec)};
}

Times since(const Times &start)
{
    const Times end = now();
    return {end.wall - start.wall, end.cpu - start.cpu};
}

// A closed surface with detail at several scales (radius 1 +- 0.1), sampled uniformly at random
// in direction, with noise of 1e-4 (about a tenth of the spacing at 5 M points) along the radius.
std::vector<float> bumpySphere(std::size_t count)
{
    std::vector<float> positions(3 * count);
#pragma omp parallel
    {
        std::mt19937 random(1234u + unsigned(omp_get_thread_num()));
        std::normal_distribution<float> gaussian;
#pragma omp for schedule(static)
        for (long i = 0; i < long(count); ++i) {
            float d[3] = {gaussian(random), gaussian(random), gaussian(random)};
            const float length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            const float radius = 1 + 0.05f * std::sin(7 * d[0] / length) * std::sin(9 * d[1] / length) +
                                 0.05f * std::sin(23 * d[2] / length) + 1e-4f * gaussian(random);
            for (int c = 0; c < 3; ++c)
                positions[3 * std::size_t(i) + c] = d[c] / length * radius;
        }
    }
    return positions;
}

// The peer: vcglib's kd-tree, built on one thread (vcglib has no parallel build), queried in parallel.
std::vector<float> kdTreeRadii(const std::vector<float> &positions, int k)
{
    const int count = int(positions.size() / 3);
    std::vector<float> radii(count, 0.0f);
    vcg::ConstDataWrapper<vcg::Point3f> points(reinterpret_cast<const vcg::Point3f *>(positions.data()), count);
    vcg::KdTree<float> tree(points);
#pragma omp parallel
    {
        vcg::KdTree<float>::PriorityQueue queue;
#pragma omp for schedule(static)
        for (int i = 0; i < count; ++i) {
            tree.doQueryK(points[i], std::min(k + 1, count), queue);
            radii[i] = std::sqrt(queue.getTopWeight());
        }
    }
    return radii;
}

} // namespace

int main(int argc, char **argv)
{
    std::size_t count = 5000000;
    std::string ply;
    int k = splat::kDefaultSplatNeighbours, repeat = 1;
    for (int a = 1; a < argc; ++a) {
        const bool hasValue = a + 1 < argc;
        if (!std::strcmp(argv[a], "--points") && hasValue)
            count = std::strtoull(argv[++a], nullptr, 10);
        else if (!std::strcmp(argv[a], "--ply") && hasValue)
            ply = argv[++a];
        else if (!std::strcmp(argv[a], "--k") && hasValue)
            k = std::atoi(argv[++a]);
        else if (!std::strcmp(argv[a], "--repeat") && hasValue)
            repeat = std::atoi(argv[++a]);
        else {
            std::fprintf(stderr, "usage: %s [--points N] [--ply FILE] [--k K] [--repeat R]\n", argv[0]);
            return 2;
        }
    }
    const std::vector<float> positions = ply.empty() ? bumpySphere(count) : splat::readPointSetFile(ply).surfels.positions;
    count = positions.size() / 3;

    std::printf("points,k,threads,kdtree_wall_s,kdtree_cpu_s,grid_wall_s,grid_cpu_s,ratio_wall,ratio_cpu,mismatches\n");
    for (int r = 0; r < repeat; ++r) {
        Times start = now();
        const std::vector<float> tree = kdTreeRadii(positions, k);
        const Times treeTimes = since(start);
        start = now();
        const std::vector<float> grid = splat::nearestNeighbourRadii(positions, k);
        const Times gridTimes = since(start);
        std::size_t mismatches = 0;
        for (std::size_t i = 0; i < count; ++i)
            mismatches += !(std::fabs(grid[i] - tree[i]) <= 1e-5f * tree[i]);
        std::printf("%zu,%d,%d,%.3f,%.3f,%.3f,%.3f,%.2f,%.2f,%zu\n", count, k, omp_get_max_threads(), treeTimes.wall,
                    treeTimes.cpu, gridTimes.wall, gridTimes.cpu, treeTimes.wall / gridTimes.wall,
                    treeTimes.cpu / gridTimes.cpu, mismatches);
        std::fflush(stdout);
    }
    return 0;
}
