// Running one program as a child process and measuring it: wall time of the whole process
// and its peak resident memory (the kernel's ru_maxrss, collected by wait4 for that child
// alone, so each measurement covers exactly one method on one model).
#ifndef GSBENCH_CHILD_PROCESS_H
#define GSBENCH_CHILD_PROCESS_H

#include <string>
#include <vector>

namespace gsbench {

struct ChildRun
{
    int exitStatus = -1;     ///< exit code; 128 + signal number when killed by a signal
    double wallSeconds = 0;  ///< from fork to reaping
    double peakMegabytes = 0; ///< ru_maxrss, MiB
};

/// Runs argv[0] (a path; no PATH search) with argv, stdout and stderr appended to `logPath`.
/// Throws std::runtime_error when the program cannot be started.
ChildRun RunChild(const std::vector<std::string> &argv, const std::string &logPath);

/// The path of the running executable, to run this program again in another mode.
std::string SelfExecutable();

} // namespace gsbench

#endif
