// The thread budget of a run (thread_budget.h): CPUs held by other processes are counted, this
// process's own threads are not, and a run takes fewer threads while another program keeps a
// CPU busy, with the same output.
#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <thread>
#include <vector>

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <vcg_ext/gaussphere/thread_budget.h>

#include "pipeline_support.h"

using namespace vcg::gaussphere;

namespace {

/// A child process spinning on a CPU for as long as it lives.
class BusyProcess
{
public:
    BusyProcess() : pid_(fork())
    {
        if (pid_ == 0) {
            volatile unsigned long spin = 0;
            for (;;) ++spin;
        }
    }
    ~BusyProcess()
    {
        if (pid_ > 0) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
    }
    bool Started() const { return pid_ > 0; }

private:
    pid_t pid_;
};

/// Threads of this process spinning for as long as the object lives.
class BusyThreads
{
public:
    explicit BusyThreads(int count)
    {
        for (int t = 0; t < count; ++t)
            threads_.emplace_back([this]() {
                while (!stop_.load(std::memory_order_relaxed)) {
                }
            });
    }
    ~BusyThreads()
    {
        stop_ = true;
        for (auto &t : threads_) t.join();
    }

private:
    std::atomic<bool> stop_{false};
    std::vector<std::thread> threads_;
};

bool ProcReadable() { return detail::SystemRunnableTasks() >= 0 && detail::OwnRunnableThreads() >= 0 && detail::SystemCpus() > 0; }

} // namespace

TEST(ThreadBudget, OwnSpinningThreadsAreRunnableAndNotCountedAsBusyElsewhere)
{
    if (!ProcReadable()) GTEST_SKIP() << "no /proc/loadavg or /proc/self/task here";
    const BusyThreads spinning(2);
    std::this_thread::sleep_for(std::chrono::milliseconds(20)); // let them start
    // The two spinners and the calling thread are runnable (running or waiting for a CPU), and
    // the system's count holds them too: CpusBusyElsewhere subtracts what this reads.
    EXPECT_GE(detail::OwnRunnableThreads(), 3);
    EXPECT_GE(detail::SystemRunnableTasks(), 3);
    EXPECT_GE(CpusBusyElsewhere(), 0);
    EXPECT_GE(detail::RunnableThreadsElsewhere(), 0); // this process's threads are not among them
}

TEST(ThreadBudget, AnotherBusyProcessTakesACpuFromTheRun)
{
    if (!ProcReadable()) GTEST_SKIP() << "no /proc/loadavg or /proc/self/task here";
    const int cpus = detail::SystemCpus();
    const BusyProcess other;
    ASSERT_TRUE(other.Started());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_GE(detail::RunnableThreadsElsewhere(), 1); // the confirmation finds it task by task
    EXPECT_GE(CpusBusyElsewhere(), 1);
    EXPECT_LE(ThreadsForRun(cpus), std::max(1, cpus - 1));
    EXPECT_GE(ThreadsForRun(cpus), 1);
    EXPECT_EQ(ThreadsForRun(1), 1);
}

TEST(ThreadBudget, ScopedThreadCountSetsAndRestores)
{
    const int before = omp_get_max_threads();
    {
        const ScopedThreadCount three(3);
        EXPECT_EQ(omp_get_max_threads(), 3);
        {
            const ScopedThreadCount none(0); // at least one
            EXPECT_EQ(omp_get_max_threads(), 1);
        }
        EXPECT_EQ(omp_get_max_threads(), 3);
    }
    EXPECT_EQ(omp_get_max_threads(), before);
}

// A run beside a busy process takes fewer threads (on a machine of 2 or more CPUs), with the
// output of a run that takes them all; adaptThreads = false takes OpenMP's maximum regardless.
TEST(ThreadBudget, ResamplingTakesFewerThreadsBesideABusyProcessWithTheSameOutput)
{
    if (!ProcReadable()) GTEST_SKIP() << "no /proc/loadavg or /proc/self/task here";
    const int cpus = detail::SystemCpus();
    if (cpus < 2) GTEST_SKIP() << "one CPU: there is no thread to give up";
    const ScopedThreadCount all(cpus);
    const gstest::PointSet s = gstest::FibonacciSphere(6000);
    OrientedPointMesh m;
    gstest::ToMesh(s, m);
    ResamplingParams fixed;
    fixed.adaptThreads = false;
    const ResamplingResult reference = ResamplePointSet(m, fixed);
    EXPECT_EQ(reference.stats.threadsUsed, cpus);
    const BusyProcess other;
    ASSERT_TRUE(other.Started());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const ResamplingResult adapted = ResamplePointSet(m, ResamplingParams());
    EXPECT_LE(adapted.stats.threadsUsed, cpus - 1);
    EXPECT_GE(adapted.stats.threadsUsed, 1);
    EXPECT_EQ(adapted.representative, reference.representative);
    EXPECT_EQ(omp_get_max_threads(), cpus); // the run restored the caller's count
    EXPECT_EQ(ResamplePointSet(m, fixed).stats.threadsUsed, cpus);
}

// A long run chooses again between stages: a process that turns busy during the run takes a
// thread from the stages after the next recheck; the caller's count comes back at the end.
TEST(ThreadBudget, RunThreadsChooseAgainAfterTheRecheckInterval)
{
    if (!ProcReadable()) GTEST_SKIP() << "no /proc/loadavg or /proc/self/task here";
    const int cpus = detail::SystemCpus();
    if (cpus < 2) GTEST_SKIP() << "one CPU: there is no thread to give up";
    const ScopedThreadCount all(cpus);
    {
        RunThreads fixed(false);
        const BusyProcess other;
        ASSERT_TRUE(other.Started());
        std::this_thread::sleep_for(std::chrono::milliseconds(kThreadRecheckMilliseconds + 20));
        fixed.Recheck();
        EXPECT_EQ(omp_get_max_threads(), cpus);
        EXPECT_EQ(fixed.Fewest(), cpus);
    }
    {
        RunThreads adapting(true);
        const int first = omp_get_max_threads();
        EXPECT_EQ(adapting.Fewest(), first);
        const BusyProcess other;
        ASSERT_TRUE(other.Started());
        adapting.Recheck(); // too soon: the count stays
        EXPECT_EQ(omp_get_max_threads(), first);
        std::this_thread::sleep_for(std::chrono::milliseconds(kThreadRecheckMilliseconds + 20));
        adapting.Recheck();
        EXPECT_LE(omp_get_max_threads(), cpus - 1);
        EXPECT_LE(adapting.Fewest(), cpus - 1);
    }
    EXPECT_EQ(omp_get_max_threads(), cpus);
}
