#pragma once
// processors_available: how many processors this process may run on, what a render's threads = 0
// starts: the CPUs of its affinity mask (taskset, numactl, a container's cpuset), at most its
// cgroup's CPU quota (a container's --cpus, a systemd CPUQuota) rounded up, and at least 1.
// std::thread::hardware_concurrency counts the machine's processors whatever the process may use:
// under `taskset -c 1` a render started two threads on one core.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>

#if defined(__linux__)
#include <sched.h>
#endif

namespace rt {

int processors_available();

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

// The CPU quota of the cgroup (v2) at `dir` and its parents, in processors (quota / period,
// rounded up); 0 when none is set.
inline int cgroup_cpu_limit(std::string dir) {
    int limit = 0;
    for (;;) {
        std::ifstream in(dir + "/cpu.max");
        std::string quota;
        double period = 0;
        if (in >> quota >> period && quota != "max" && period > 0) {
            const double q = std::strtod(quota.c_str(), nullptr);
            if (q > 0) {
                const int n = std::max(1, int(std::ceil(q / period)));
                limit = limit == 0 ? n : std::min(limit, n);
            }
        }
        const size_t slash = dir.find_last_of('/');
        if (slash == std::string::npos || dir == "/sys/fs/cgroup") break;
        dir.erase(slash);
    }
    return limit;
}

} // namespace detail

inline int processors_available() {
    int n = 0;
#if defined(__linux__)
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0) n = CPU_COUNT(&set);
    // The process's cgroup (v2: a line "0::/path" of /proc/self/cgroup).
    std::ifstream cgroups("/proc/self/cgroup");
    for (std::string line; std::getline(cgroups, line);) {
        if (line.rfind("0::", 0) != 0) continue;
        const int limit = detail::cgroup_cpu_limit("/sys/fs/cgroup" + line.substr(3));
        if (limit > 0) n = n > 0 ? std::min(n, limit) : limit;
    }
#endif
    if (n <= 0) n = int(std::thread::hardware_concurrency());
    return std::max(1, n);
}

} // namespace rt
