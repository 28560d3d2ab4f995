// render/processors.h: a render's threads = 0 means the processors this process may use (its
// affinity mask and its cgroup's CPU quota), not the machine's.

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <rtweekend/render/processors.h>
#include <rtweekend/rtweekend.h>

#include <filesystem>
#include <fstream>

#if defined(__linux__)
#include <sched.h>
#endif

namespace test_processors {

using namespace rt;

TEST_CASE("processors: threads = 0 starts one thread per processor of the affinity mask") {
#if defined(__linux__)
    cpu_set_t saved;
    REQUIRE(sched_getaffinity(0, sizeof saved, &saved) == 0);
    CHECK(processors_available() >= 1);
    CHECK(processors_available() <= CPU_COUNT(&saved));
    // As `taskset -c N` would: one processor of those allowed.
    int first = 0;
    while (!CPU_ISSET(first, &saved)) ++first;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(first, &one);
    REQUIRE(sched_setaffinity(0, sizeof one, &one) == 0);
    const int available = processors_available();
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -1), 0.5, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    camera cam = test::test_camera(8, 8, 2, 4);
    cam.settings.threads = 0;
    const render_result r = render(cam, world);
    sched_setaffinity(0, sizeof saved, &saved);
    CHECK(available == 1);
    CHECK(r.stats.threads == 1);
#endif
}

TEST_CASE("processors: a cgroup's CPU quota bounds them, rounded up, the lowest on the way up") {
    test::scratch_dir dir("processors_cgroup");
    const std::filesystem::path top = dir.path / "top", mid = top / "mid", leaf = mid / "leaf";
    std::filesystem::create_directories(leaf);
    auto write = [](const std::filesystem::path& p, const char* text) { std::ofstream(p / "cpu.max") << text; };
    write(top, "max 100000\n");
    CHECK(detail::cgroup_cpu_limit(leaf.string()) == 0); // no quota anywhere
    write(mid, "150000 100000\n");
    CHECK(detail::cgroup_cpu_limit(leaf.string()) == 2); // 1.5 processors: 2
    write(leaf, "300000 100000\n");
    CHECK(detail::cgroup_cpu_limit(leaf.string()) == 2); // the parent's is lower
    write(top, "50000 100000\n");
    CHECK(detail::cgroup_cpu_limit(leaf.string()) == 1); // half a processor: 1
}

} // namespace test_processors
