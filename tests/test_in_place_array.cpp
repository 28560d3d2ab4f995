// in_place_array (rtweekend/core/in_place_array.h): objects built in place, in order, each
// destroyed exactly once, at fixed addresses.

#include <rtweekend/core/in_place_array.h>

#include <doctest/doctest.h>

#include <string>

namespace test_in_place_array {

using namespace rt;

namespace {

// Counts its constructions and destructions, and remembers what it was built from.
struct counted {
    static inline int alive = 0, destroyed = 0;
    int id;
    std::string name; // a member with a destructor of its own
    counted(int id, std::string name) : id(id), name(std::move(name)) { ++alive; }
    counted(const counted&) = delete;
    ~counted() {
        --alive;
        ++destroyed;
    }
};

} // namespace

TEST_CASE("in_place_array builds objects in order and destroys each of them once") {
    counted::alive = counted::destroyed = 0;
    {
        in_place_array<counted, 4> a;
        CHECK(a.size() == 0);
        counted& first = a.emplace_back(7, "seven");
        counted& second = a.emplace_back(9, std::string(40, 'x')); // past the small-string buffer
        CHECK(a.size() == 2);
        CHECK(counted::alive == 2);
        CHECK(&a[0] == &first);
        CHECK(&a[1] == &second);
        CHECK(a[0].id == 7);
        CHECK(a[0].name == "seven");
        CHECK(a[1].id == 9);
        CHECK(a[1].name.size() == 40);
        // Objects keep their addresses as more are built (the room is fixed).
        a.emplace_back(11, "eleven");
        CHECK(&a[0] == &first);
        CHECK(a[2].id == 11);
        const in_place_array<counted, 4>& read_only = a;
        CHECK(read_only[2].name == "eleven");
    }
    // Three built, three destroyed: the fourth slot never held an object.
    CHECK(counted::alive == 0);
    CHECK(counted::destroyed == 3);
}

} // namespace test_in_place_array
