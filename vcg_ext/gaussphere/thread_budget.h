// How many threads a run takes: OpenMP's maximum, less the CPUs that other programs keep busy.
//
// Why: at the end of every parallel loop libgomp's threads wait for each other by spinning for
// up to milliseconds before they sleep (its default wait policy). When another program keeps a
// CPU busy, a team as large as the machine spins through the time slices its own late member
// needs. Measured on this project's 2-core machine, the igea (134,345 points) beside one
// CPU-bound process of another session (another terminal, a desktop program, a second batch run:
// Linux's autogroups share the CPUs equally between sessions, whatever their nice values): 0.31-0.49 s
// on 2 threads against 0.09-0.10 s on one (0.05-0.06 s on 2 threads idle; OMP_WAIT_POLICY=passive:
// 0.10-0.12 s loaded, 4 % slower idle). A library cannot choose the wait policy (libgomp reads
// OMP_WAIT_POLICY when it loads), so a run takes as many threads as there are CPUs nobody else
// holds, and at least one. The result does not depend on the thread count. The price: a process
// niced within the caller's own session weighs little beside it, yet takes a thread too (igea:
// 0.10 s on one thread where two would take 0.06 s).
//
// Busy CPUs: the runnable tasks of the whole system (the fourth field of /proc/loadavg, a count
// taken now, not an average) less this process's own runnable threads (/proc/self/task); when
// that is not zero, confirmed by the runnable threads of the other processes' /proc entries (not
// the kernel's); the least of a few readings a millisecond apart, so that a task waking for a
// moment does not count.
// Elsewhere than on Linux, or when /proc cannot be read: OpenMP's maximum.
#ifndef VCG_EXT_GAUSSPHERE_THREAD_BUDGET_H
#define VCG_EXT_GAUSSPHERE_THREAD_BUDGET_H

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>

#include <omp.h>

#if defined(__linux__)
#include <dirent.h>
#include <unistd.h>
#endif

namespace vcg {
namespace gaussphere {

/// Readings of the busy CPUs per decision, and their spacing.
constexpr int kBusyCpuReadings = 3;
constexpr int kBusyCpuReadingGapMicroseconds = 1000;
/// How old a run's thread count may grow before RunThreads::Recheck chooses again.
constexpr int kThreadRecheckMilliseconds = 200;

namespace detail {

#if defined(__linux__)
/// Runnable tasks of the whole system now (/proc/loadavg), or -1 if unknown.
inline int SystemRunnableTasks()
{
    std::FILE *f = std::fopen("/proc/loadavg", "r");
    if (!f) return -1;
    double average[3];
    int runnable = -1, total = 0;
    const int read = std::fscanf(f, "%lf %lf %lf %d/%d", &average[0], &average[1], &average[2], &runnable, &total);
    std::fclose(f);
    return read == 5 ? runnable : -1;
}

/// The fields after the name of the stat file `path` ("pid (name) S ppid ..."; the name may hold
/// spaces and parentheses), copied to `fields`, or false if the task ended meanwhile.
inline bool ReadStatFields(const char *path, char (&fields)[512])
{
    std::FILE *f = std::fopen(path, "r");
    if (!f) return false;
    char line[512];
    const size_t length = std::fread(line, 1, sizeof line - 1, f);
    std::fclose(f);
    line[length] = '\0';
    const char *nameEnd = std::strrchr(line, ')');
    if (!nameEnd || nameEnd[1] != ' ') return false;
    std::snprintf(fields, sizeof fields, "%s", nameEnd + 2);
    return true;
}

/// Whether the task whose stat file is `path` is runnable now (state R).
inline bool TaskRunnable(const char *path)
{
    char fields[512];
    return ReadStatFields(path, fields) && fields[0] == 'R';
}

/// Whether process `pid` is a kernel thread (kthreadd, pid 2, or one of its children): their
/// bursts (compacting memory after a run's huge pages, say) last milliseconds, not a whole run.
inline bool KernelThread(long pid)
{
    if (pid == 2) return true;
    char path[64], fields[512];
    std::snprintf(path, sizeof path, "/proc/%ld/stat", pid);
    long parent = -1;
    return ReadStatFields(path, fields) && std::sscanf(fields, "%*c %ld", &parent) == 1 && parent == 2;
}

/// Runnable threads of the process whose /proc folder is `process` ("self" or a pid), or -1 if
/// its task list cannot be read.
inline int RunnableThreadsOf(const char *process)
{
    char folder[64];
    std::snprintf(folder, sizeof folder, "/proc/%.20s/task", process);
    DIR *tasks = opendir(folder);
    if (!tasks) return -1;
    int runnable = 0;
    while (const dirent *task = readdir(tasks)) {
        if (task->d_name[0] == '.') continue;
        char path[128];
        std::snprintf(path, sizeof path, "%s/%.32s/stat", folder, task->d_name);
        runnable += TaskRunnable(path);
    }
    closedir(tasks);
    return runnable;
}

/// Threads of this process that are runnable now, or -1 if unknown.
inline int OwnRunnableThreads() { return RunnableThreadsOf("self"); }

/// Runnable threads of every other process but the kernel's, from their /proc entries, or -1 if
/// unknown: the count /proc/loadavg gives, task by task (on this project's virtual machine the
/// loadavg count held one task more than any /proc entry showed runnable for milliseconds after
/// one run in twenty or so, and kernel threads ran for milliseconds between short runs).
inline int RunnableThreadsElsewhere()
{
    DIR *processes = opendir("/proc");
    if (!processes) return -1;
    const long self = long(getpid());
    int runnable = 0;
    while (const dirent *process = readdir(processes)) {
        char *end = nullptr;
        const long pid = std::strtol(process->d_name, &end, 10);
        if (end == process->d_name || *end != '\0' || pid == self || KernelThread(pid)) continue;
        runnable += std::max(0, RunnableThreadsOf(process->d_name));
    }
    closedir(processes);
    return runnable;
}

/// CPUs of the system, or -1 if unknown.
inline int SystemCpus() { return int(sysconf(_SC_NPROCESSORS_ONLN)); }
#else
inline int SystemRunnableTasks() { return -1; }
inline int OwnRunnableThreads() { return -1; }
inline int RunnableThreadsElsewhere() { return -1; }
inline int SystemCpus() { return -1; }
#endif

} // namespace detail

/// CPUs that runnable tasks of other processes hold now (the least of kBusyCpuReadings
/// readings), or -1 if unknown.
inline int CpusBusyElsewhere()
{
    int least = -1;
    for (int r = 0; r < kBusyCpuReadings; ++r) {
        if (r > 0) std::this_thread::sleep_for(std::chrono::microseconds(kBusyCpuReadingGapMicroseconds));
        const int system = detail::SystemRunnableTasks(), own = detail::OwnRunnableThreads();
        if (system < 0 || own < 0) return -1;
        int elsewhere = std::max(0, system - own);
        // The cheap count says busy: confirm it task by task (a scan of /proc, ~1 ms).
        if (elsewhere > 0) elsewhere = std::min(elsewhere, std::max(0, detail::RunnableThreadsElsewhere()));
        least = least < 0 ? elsewhere : std::min(least, elsewhere);
        if (least == 0) break;
    }
    return least;
}

/// The threads a run should take, in [1, maxThreads]: maxThreads less the CPUs busy elsewhere
/// beyond the idle ones (file header); maxThreads when that cannot be told.
inline int ThreadsForRun(int maxThreads)
{
    maxThreads = std::max(1, maxThreads);
    const int cpus = detail::SystemCpus(), busy = cpus > 0 ? CpusBusyElsewhere() : -1;
    if (busy < 0) return maxThreads;
    return std::max(1, std::min(maxThreads, cpus - busy));
}

/// Sets OpenMP's thread count for the parallel regions the calling thread starts, and restores
/// the previous one when it ends.
class ScopedThreadCount
{
public:
    explicit ScopedThreadCount(int threads) : saved_(omp_get_max_threads()) { omp_set_num_threads(std::max(1, threads)); }
    ~ScopedThreadCount() { omp_set_num_threads(saved_); }
    ScopedThreadCount(const ScopedThreadCount &) = delete;
    ScopedThreadCount &operator=(const ScopedThreadCount &) = delete;

private:
    int saved_;
};

/// The thread count of a run: chosen when it starts (ThreadsForRun of the caller's OpenMP
/// maximum, or that maximum when not adapting), chosen again by Recheck() between stages once
/// kThreadRecheckMilliseconds have passed (a run of millions of points lasts seconds, and the load
/// with it may change), and the caller's count restored when it ends.
class RunThreads
{
public:
    explicit RunThreads(bool adapt) : caller_(omp_get_max_threads()), adapt_(adapt), restore_(caller_) { Choose(); }
    /// Between parallel regions only.
    void Recheck()
    {
        if (adapt_ && std::chrono::steady_clock::now() - chosenAt_ >= std::chrono::milliseconds(kThreadRecheckMilliseconds)) Choose();
    }
    /// The fewest threads a stage of the run has taken so far.
    int Fewest() const { return fewest_; }

private:
    void Choose()
    {
        const int threads = adapt_ ? ThreadsForRun(caller_) : caller_;
        omp_set_num_threads(threads);
        fewest_ = fewest_ == 0 ? threads : std::min(fewest_, threads);
        chosenAt_ = std::chrono::steady_clock::now();
    }

    int caller_;
    bool adapt_;
    ScopedThreadCount restore_; // sets the caller's count now, restores it at the end
    int fewest_ = 0;
    std::chrono::steady_clock::time_point chosenAt_;
};

} // namespace gaussphere
} // namespace vcg

#endif
