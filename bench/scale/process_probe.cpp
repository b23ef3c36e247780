#include "process_probe.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <malloc.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace gsscale {

std::size_t ResidentBytes()
{
    std::ifstream statm("/proc/self/statm");
    std::size_t size = 0, resident = 0;
    statm >> size >> resident;
    return resident * std::size_t(sysconf(_SC_PAGESIZE));
}

std::size_t PeakResidentBytes()
{
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.compare(0, 6, "VmHWM:") == 0) return std::size_t(std::strtoull(line.c_str() + 6, nullptr, 10)) * 1024;
    return 0;
}

bool ResetPeakResident()
{
    std::FILE *f = std::fopen("/proc/self/clear_refs", "w");
    if (!f) return false;
    const bool written = std::fputs("5", f) >= 0;
    return std::fclose(f) == 0 && written;
}

double CpuSeconds()
{
    rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec + 1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

void TrimHeap() { malloc_trim(0); }

std::size_t HeapInUseBytes()
{
    const struct mallinfo2 info = mallinfo2();
    return info.uordblks + info.hblkhd;
}

void UseMmapForLargeBlocks()
{
    mallopt(M_MMAP_THRESHOLD, 256 * 1024); // setting it also stops the dynamic adjustment
}

std::string LoadAverage()
{
    std::ifstream in("/proc/loadavg");
    double a = 0, b = 0, c = 0;
    in >> a >> b >> c;
    char text[64];
    std::snprintf(text, sizeof(text), "%.2f %.2f %.2f", a, b, c);
    return text;
}

std::string MachineDescription()
{
    std::ifstream cpuinfo("/proc/cpuinfo"), meminfo("/proc/meminfo");
    std::string line, model = "unknown CPU";
    while (std::getline(cpuinfo, line))
        if (line.compare(0, 10, "model name") == 0) { model = line.substr(line.find(':') + 2); break; }
    long long memKb = 0;
    while (std::getline(meminfo, line))
        if (line.compare(0, 9, "MemTotal:") == 0) { memKb = std::atoll(line.c_str() + 9); break; }
    std::ostringstream out;
    out << model << ", " << std::thread::hardware_concurrency() << " cores online, "
        << (memKb + 512 * 1024) / (1024 * 1024) << " GiB RAM";
    return out.str();
}

ChildOutput RunSelf(const std::vector<std::string> &args, const std::vector<std::string> &env)
{
    int pipeFd[2];
    if (pipe(pipeFd) != 0) throw std::runtime_error("pipe failed");
    std::vector<std::string> argvText;
    argvText.push_back("/proc/self/exe");
    argvText.insert(argvText.end(), args.begin(), args.end());
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        // Child: stdout into the pipe, then a fresh image of this program (a fresh heap,
        // a fresh peak RSS, a fresh OpenMP runtime reading OMP_NUM_THREADS).
        dup2(pipeFd[1], STDOUT_FILENO);
        close(pipeFd[0]);
        close(pipeFd[1]);
        for (const std::string &e : env) putenv(const_cast<char *>(e.c_str()));
        std::vector<char *> argv;
        for (std::string &a : argvText) argv.push_back(&a[0]);
        argv.push_back(nullptr);
        execv("/proc/self/exe", argv.data());
        std::perror("execv");
        _exit(127);
    }
    close(pipeFd[1]);
    ChildOutput result;
    char buffer[4096];
    ssize_t got;
    while ((got = read(pipeFd[0], buffer, sizeof(buffer))) > 0) result.stdoutText.append(buffer, size_t(got));
    close(pipeFd[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    result.exitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return result;
}

} // namespace gsscale
