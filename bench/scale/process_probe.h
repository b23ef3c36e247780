// Measurements of the running process (Linux): resident memory, its peak, CPU time, and
// running this program again as a child.
//
// Peak memory per stage: writing "5" to /proc/self/clear_refs resets the kernel's
// high-water mark (VmHWM, which is also what getrusage's ru_maxrss reports) to the
// current RSS. Reading and resetting it at every progress callback gives the peak of each
// stage separately; the process peak is the largest of them.
#ifndef GSSCALE_PROCESS_PROBE_H
#define GSSCALE_PROCESS_PROBE_H

#include <cstddef>
#include <string>
#include <vector>

namespace gsscale {

/// Current resident set size, bytes (/proc/self/statm).
std::size_t ResidentBytes();

/// Peak resident set size since the start or the last ResetPeakResident(), bytes
/// (VmHWM of /proc/self/status).
std::size_t PeakResidentBytes();

/// Resets the peak to the current RSS; false when the kernel does not allow it.
bool ResetPeakResident();

/// User + system CPU time of the process (all threads), seconds.
double CpuSeconds();

/// Bytes the allocator holds for live blocks (malloc's arenas and its own mmaps): what RSS would
/// be without fragmentation and cached free memory.
std::size_t HeapInUseBytes();

/// Returns freed heap memory to the kernel so that RSS reflects live data only.
void TrimHeap();

/// Makes glibc serve every block of 256 KiB or more with its own mmap, returned to the
/// kernel when freed. By default glibc raises that threshold up to 32 MiB after the first
/// such free, so at a million points freed buffers of 4-16 MB stay in the heap and RSS
/// counts them: it would measure the allocator's caching instead of the live buffers, and
/// differently at each size (at 20M points every per-point buffer exceeds 32 MiB anyway).
void UseMmapForLargeBlocks();

/// The system's load averages over 1, 5 and 15 minutes, as in /proc/loadavg.
std::string LoadAverage();

/// "model name" of the first CPU, the online core count and the total memory.
std::string MachineDescription();

struct ChildOutput
{
    int exitStatus = -1;  ///< exit code, or 128 + signal
    std::string stdoutText;
};

/// Runs this executable again with `args` (argv[1...]) and the extra environment
/// variables `env` ("NAME=value"); its stdout is captured, its stderr passes through.
ChildOutput RunSelf(const std::vector<std::string> &args, const std::vector<std::string> &env);

} // namespace gsscale

#endif
