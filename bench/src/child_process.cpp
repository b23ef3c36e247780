#include "child_process.h"

#include <chrono>
#include <climits>
#include <fcntl.h>
#include <stdexcept>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace gsbench {

ChildRun RunChild(const std::vector<std::string> &argv, const std::string &logPath)
{
    std::vector<char *> cargs;
    for (const std::string &a : argv) cargs.push_back(const_cast<char *>(a.c_str()));
    cargs.push_back(nullptr);

    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        const int log = open(logPath.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        if (log >= 0) {
            dup2(log, STDOUT_FILENO);
            dup2(log, STDERR_FILENO);
            close(log);
        }
        execv(cargs[0], cargs.data());
        _exit(127);
    }
    int status = 0;
    struct rusage usage = {};
    if (wait4(pid, &status, 0, &usage) < 0) throw std::runtime_error("wait4 failed for " + argv[0]);
    ChildRun run;
    run.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    run.peakMegabytes = usage.ru_maxrss / 1024.0; // Linux reports kilobytes
    if (WIFEXITED(status)) run.exitStatus = WEXITSTATUS(status);
    else if (WIFSIGNALED(status)) run.exitStatus = 128 + WTERMSIG(status);
    if (run.exitStatus == 127) throw std::runtime_error("cannot run " + argv[0] + " (see " + logPath + ")");
    return run;
}

std::string SelfExecutable()
{
    char path[PATH_MAX];
    const ssize_t n = readlink("/proc/self/exe", path, sizeof(path) - 1);
    if (n <= 0) throw std::runtime_error("cannot resolve /proc/self/exe");
    return std::string(path, size_t(n));
}

} // namespace gsbench
