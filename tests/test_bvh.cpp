// The BVH builder (rtweekend/scene/bvh.h): structural invariants checked by walking the tree
// independently of the traversal: every primitive stored once, leaves of one kind and bounded
// size, every box containing everything below it.

#include <rtweekend/scene/bvh.h>
#include <rtweekend/core/rng.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace test_bvh {

using namespace rt;

namespace {

box3f random_box(pcg32& rng, float spread, float size) {
    vec3f c{spread * rng.next_float(), spread * rng.next_float(), spread * rng.next_float()};
    vec3f e{size * rng.next_float(), size * rng.next_float(), size * rng.next_float()};
    box3f b;
    b.grow(c - e);
    b.grow(c + e);
    return b;
}

// The BVH over triangles given by their corners, with spatial splits down to nodes of more than
// 16 triangles; `options` is what it was built with.
wide_bvh build_with_spatial_splits(const std::vector<std::array<vec3f, 3>>& corners, bvh_build_options& options) {
    std::vector<bvh_primitive> prims;
    for (uint32_t i = 0; i < corners.size(); ++i) {
        box3f b;
        for (const vec3f& v : corners[i]) b.grow(v);
        prims.push_back({b, shape_id<triangle_set>, i});
    }
    options.split_kind = shape_id<triangle_set>;
    options.split_corners = [&corners](uint32_t i) { return corners[i]; };
    options.spatial_min_count = 16;
    return build_wide_bvh(prims, options);
}

bool contains(const wide_node& node, int slot, const box3f& b) {
    return node.bounds[0][slot] <= b.lo.x && node.bounds[1][slot] <= b.lo.y && node.bounds[2][slot] <= b.lo.z &&
           node.bounds[3][slot] >= b.hi.x && node.bounds[4][slot] >= b.hi.y && node.bounds[5][slot] >= b.hi.z;
}

struct checker {
    const wide_bvh& bvh;
    const std::vector<bvh_primitive>& prims; // by kind, then index: by_kind[kind][index]
    std::vector<std::vector<const bvh_primitive*>> by_kind;
    std::vector<std::vector<int>> seen;
    uint32_t max_leaf;
    int problems = 0;

    checker(const wide_bvh& b, const std::vector<bvh_primitive>& p, uint32_t max_leaf)
        : bvh(b), prims(p), by_kind(shape_kind_count), seen(shape_kind_count), max_leaf(max_leaf) {
        for (const auto& q : prims) {
            auto t = size_t(q.kind);
            if (by_kind[t].size() <= q.index) by_kind[t].resize(q.index + 1);
            by_kind[t][q.index] = &q;
        }
        for (size_t t = 0; t < by_kind.size(); ++t) seen[t].assign(by_kind[t].size(), 0);
    }

    // Every primitive under `ref`, checked to lie inside `box` (when given).
    void walk(uint32_t ref, const wide_node* parent, int slot) {
        if (bvh_ref::is_leaf(ref)) {
            auto t = size_t(bvh_ref::kind(ref));
            uint32_t first = bvh_ref::first(ref), count = bvh_ref::count(ref);
            if (count > max_leaf) ++problems;
            for (uint32_t k = first; k < first + count; ++k) {
                uint32_t index = bvh.order[t].at(k);
                ++seen[t].at(index);
                if (parent && !contains(*parent, slot, by_kind[t][index]->bounds)) ++problems;
            }
            return;
        }
        const wide_node& node = bvh.nodes.at(bvh_ref::node_index(ref));
        for (int i = 0; i < bvh_width; ++i) {
            if (node.child[i] == bvh_ref::empty) continue;
            if (parent) { // the child's box lies inside the parent's slot box
                box3f child{{node.bounds[0][i], node.bounds[1][i], node.bounds[2][i]},
                            {node.bounds[3][i], node.bounds[4][i], node.bounds[5][i]}};
                if (!contains(*parent, slot, child)) ++problems;
            }
            walk(node.child[i], &node, i);
        }
    }
};

} // namespace

TEST_CASE("bvh: every primitive exactly once, leaves bounded and of one kind, boxes nest") {
    pcg32 rng = sample_rng(5, 0, 0);
    std::vector<bvh_primitive> prims;
    uint32_t spheres = 0, triangles = 0;
    for (int i = 0; i < 5000; ++i) {
        bool tri = rng.next_float() < 0.7f;
        prims.push_back({random_box(rng, 100, tri ? 1.0f : 3.0f), tri ? shape_id<triangle_set> : shape_id<sphere_set>,
                         tri ? triangles++ : spheres++});
    }
    bvh_build_options options;
    wide_bvh bvh = build_wide_bvh(prims, options);
    CHECK(bvh.stats.primitives == 5000);
    CHECK(bvh.order[0].size() == spheres);
    CHECK(bvh.order[1].size() == triangles);
    REQUIRE_FALSE(bvh_ref::is_leaf(bvh.root));
    CHECK(bvh.stats.nodes == bvh.nodes.size());
    CHECK(bvh.stats.bytes() == bvh.nodes.size() * sizeof(wide_node));
    // A tree over 5000 primitives in leaves of <= 16: at least log_w(5000 / 16) deep for nodes of
    // w children, 2.8 for 8 and 2.1 for 16, so 3 in whole levels.
    CHECK(bvh.stats.depth >= 3);

    checker c(bvh, prims, options.max_leaf_size);
    c.walk(bvh.root, nullptr, 0);
    CHECK(c.problems == 0);
    for (size_t t = 0; t < 2; ++t)
        for (int n : c.seen[t]) CHECK(n == 1);

    // Every node has at least two children (one would be a wasted visit), and on average more
    // than three: a binary tree would have exactly two.
    size_t children = 0;
    for (const auto& node : bvh.nodes) {
        size_t n = 0;
        for (uint32_t ch : node.child) n += ch != bvh_ref::empty;
        CHECK(n >= 2);
        children += n;
    }
    CHECK(double(children) / double(bvh.nodes.size()) > 3.0);
}

TEST_CASE("bvh: the wide collapse leaves no inner child its parent has room to take in") {
    // The binary tree is collapsed into wide nodes at least SAH cost (bvh.h, plan_collapse).
    // An inner child C of m children under a parent of k children, where k - 1 + m <= bvh_width, could
    // be dissolved, its children moved up into the parent: every box stays the same and C's
    // visit is saved, a lower cost. So the cheapest collapse has no such child, whatever the
    // scene. Boxes of positive area, so that every node's visit costs something.
    for (uint64_t seed : {1u, 2u, 3u}) {
        pcg32 rng = sample_rng(seed, 0, 0);
        std::vector<bvh_primitive> prims;
        const int n = 500 + 1500 * int(seed);
        for (int i = 0; i < n; ++i)
            prims.push_back({random_box(rng, 100, 0.2f + 4.0f * rng.next_float()), shape_id<sphere_set>, uint32_t(i)});
        const wide_bvh bvh = build_wide_bvh(prims, bvh_build_options{});
        auto children = [&](uint32_t node) {
            int count = 0;
            for (uint32_t c : bvh.nodes[node].child) count += c != bvh_ref::empty;
            return count;
        };
        int absorbable = 0;
        size_t slots = 0;
        for (uint32_t p = 0; p < bvh.nodes.size(); ++p) {
            const int k = children(p);
            slots += size_t(k);
            for (uint32_t c : bvh.nodes[p].child)
                if (c != bvh_ref::empty && !bvh_ref::is_leaf(c) &&
                    k - 1 + children(bvh_ref::node_index(c)) <= bvh_width)
                    ++absorbable;
        }
        CAPTURE(seed);
        CHECK(absorbable == 0);
        MESSAGE("children per node: " << double(slots) / double(bvh.nodes.size()));
    }
}

TEST_CASE("bvh: small and degenerate inputs") {
    // Nothing: an empty root.
    wide_bvh none = build_wide_bvh({});
    CHECK(none.root == bvh_ref::empty);
    CHECK(none.nodes.empty());

    // Three spheres: no nodes, the root is one leaf (a tiny scene needs no hierarchy).
    std::vector<bvh_primitive> three;
    pcg32 rng = sample_rng(9, 0, 0);
    for (uint32_t i = 0; i < 3; ++i) three.push_back({random_box(rng, 10, 1), shape_id<sphere_set>, i});
    wide_bvh small = build_wide_bvh(three);
    CHECK(small.nodes.empty());
    REQUIRE(bvh_ref::is_leaf(small.root));
    CHECK(bvh_ref::count(small.root) == 3);
    CHECK(bvh_ref::first(small.root) == 0);

    // Two kinds in a tiny scene: split by kind, since a leaf holds one kind.
    std::vector<bvh_primitive> mixed = three;
    mixed.push_back({random_box(rng, 10, 1), shape_id<triangle_set>, 0});
    wide_bvh m = build_wide_bvh(mixed);
    REQUIRE_FALSE(bvh_ref::is_leaf(m.root));
    checker cm(m, mixed, bvh_build_options{}.max_leaf_size);
    cm.walk(m.root, nullptr, 0);
    CHECK(cm.problems == 0);

    // 10000 identical boxes: no plane separates them; the build must still finish, with
    // bounded leaves and a bounded depth (object-median splits).
    std::vector<bvh_primitive> same;
    box3f b = random_box(rng, 1, 1);
    for (uint32_t i = 0; i < 10000; ++i) same.push_back({b, shape_id<triangle_set>, i});
    wide_bvh s = build_wide_bvh(same);
    checker cs(s, same, bvh_build_options{}.max_leaf_size);
    cs.walk(s.root, nullptr, 0);
    CHECK(cs.problems == 0);
    for (int n : cs.seen[1]) CHECK(n == 1);
    CHECK(s.stats.depth < 96);

    // Centres spread over a denormal width along x (1e-39 apart at most): bins / extent overflows
    // to infinity there, so that axis offers no planes (before the fix, 0 * inf made a NaN bin,
    // undefined behaviour in its conversion to int: the xml_scene fuzz harness found it). y
    // still splits them.
    std::vector<bvh_primitive> thin;
    for (uint32_t i = 0; i < 1000; ++i) {
        box3f t;
        t.grow(vec3f(float(i % 2) * 1e-39f, float(i), 0));
        t.grow(vec3f(float(i % 2) * 1e-39f, float(i) + 0.5f, 1));
        thin.push_back({t, shape_id<triangle_set>, i});
    }
    wide_bvh th = build_wide_bvh(thin);
    checker ct(th, thin, bvh_build_options{}.max_leaf_size);
    ct.walk(th.root, nullptr, 0);
    CHECK(ct.problems == 0);
    for (int n : ct.seen[1]) CHECK(n == 1);
    CHECK(th.stats.depth < 32); // split along y: a balanced tree of 1000 leaves' worth

    // Leaf size is honoured, up to the encoding's limit of 16.
    bvh_build_options big;
    big.max_leaf_size = 64;
    big.primitive_cost = 0.001f; // leaves are nearly free: the builder wants them as big as allowed
    wide_bvh l = build_wide_bvh(same, big);
    checker cl(l, same, bvh_ref::max_leaf_size);
    cl.walk(l.root, nullptr, 0);
    CHECK(cl.problems == 0);
}

TEST_CASE("bvh: spatial splits keep every part of every triangle inside a leaf box that holds it") {
    // Small triangles and, one in twenty, long thin ones across the whole scene, which boxes by
    // centroids cannot separate from the small ones: the builder splits the long ones by planes
    // through them (spatial_min_count 16: down to small nodes).
    pcg32 rng = sample_rng(21, 0, 0);
    auto u = [&] { return rng.next_float(); };
    std::vector<std::array<vec3f, 3>> corners;
    for (uint32_t i = 0; i < 2000; ++i) {
        const vec3f c{100 * u(), 100 * u(), 100 * u()};
        const float length = i % 20 == 0 ? 120.0f : 4.0f;
        const vec3f long_edge{length * (u() - 0.5f), length * (u() - 0.5f), length * (u() - 0.5f)};
        const vec3f short_edge{u() - 0.5f, u() - 0.5f, u() - 0.5f};
        corners.push_back({c, c + long_edge, c + short_edge});
    }
    bvh_build_options options;
    wide_bvh bvh = build_with_spatial_splits(corners, options);
    const std::vector<uint32_t>& order = bvh.order[size_t(shape_id<triangle_set>)];
    CHECK(order.size() > corners.size() + corners.size() / 20); // more than 5 % copies: splits happened
    CHECK(order.size() < 2 * corners.size()); // and within reason (budget 1.3, per split at most its node)

    // Each triangle's leaf boxes (the slots that hold a leaf naming it), found by walking the tree.
    std::vector<std::vector<box3f>> boxes(corners.size());
    int problems = 0;
    std::vector<uint32_t> pending{bvh.root};
    REQUIRE_FALSE(bvh_ref::is_leaf(bvh.root));
    while (!pending.empty()) {
        const wide_node& node = bvh.nodes.at(bvh_ref::node_index(pending.back()));
        pending.pop_back();
        for (int i = 0; i < bvh_width; ++i) {
            const uint32_t child = node.child[i];
            if (child == bvh_ref::empty) continue;
            const box3f slot{{node.bounds[0][i], node.bounds[1][i], node.bounds[2][i]},
                             {node.bounds[3][i], node.bounds[4][i], node.bounds[5][i]}};
            if (!bvh_ref::is_leaf(child)) {
                pending.push_back(child);
                continue;
            }
            if (bvh_ref::kind(child) != shape_id<triangle_set> || bvh_ref::count(child) > options.max_leaf_size) ++problems;
            std::vector<uint32_t> in_leaf;
            for (uint32_t k = bvh_ref::first(child); k < bvh_ref::first(child) + bvh_ref::count(child); ++k) {
                const uint32_t t = order.at(k);
                boxes.at(t).push_back(slot);
                in_leaf.push_back(t);
            }
            // A leaf names a triangle once: its parts went to different sides of each split.
            std::sort(in_leaf.begin(), in_leaf.end());
            if (std::adjacent_find(in_leaf.begin(), in_leaf.end()) != in_leaf.end()) ++problems;
        }
    }
    CHECK(problems == 0);
    // Points of each triangle, in double: corners, edge midpoints and random interior points. Each
    // must lie in one of the triangle's leaf boxes, or a ray hitting it there would miss it.
    int outside = 0;
    for (size_t t = 0; t < corners.size(); ++t) {
        REQUIRE_FALSE(boxes[t].empty()); // every triangle is in some leaf
        const vec3 a = corners[t][0].to_double(), b = corners[t][1].to_double(), c = corners[t][2].to_double();
        std::vector<vec3> points{a, b, c, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)};
        for (int k = 0; k < 40; ++k) {
            double s1 = u(), s2 = u();
            if (s1 + s2 > 1) s1 = 1 - s1, s2 = 1 - s2;
            points.push_back(a + s1 * (b - a) + s2 * (c - a));
        }
        for (const vec3& p : points) {
            bool inside = false;
            for (const box3f& box : boxes[t])
                inside = inside || (box.lo.x <= p.x() && p.x() <= box.hi.x && box.lo.y <= p.y() && p.y() <= box.hi.y &&
                                    box.lo.z <= p.z() && p.z() <= box.hi.z);
            outside += !inside;
        }
    }
    CHECK(outside == 0);
}

TEST_CASE("bvh: spatial splits of triangles that all overlap stay within their budget") {
    // 3000 copies of one large triangle and 3000 slivers across it: every plane through them cuts
    // them all, which a split could repeat level after level. The budget (references per
    // triangle) and the room for references bound the work; the tree stays valid.
    std::vector<std::array<vec3f, 3>> corners;
    pcg32 rng = sample_rng(4, 0, 0);
    for (uint32_t i = 0; i < 6000; ++i) {
        const float y = i < 3000 ? 0.0f : 100.0f * rng.next_float();
        corners.push_back(i < 3000 ? std::array<vec3f, 3>{vec3f{0, 0, 0}, vec3f{100, 0, 1}, vec3f{0, 100, 2}}
                                   : std::array<vec3f, 3>{vec3f{0, y, 0}, vec3f{100, y, 0.5f}, vec3f{50, y + 0.01f, 3}});
    }
    bvh_build_options options;
    wide_bvh bvh = build_with_spatial_splits(corners, options);
    const size_t n = corners.size(), references = bvh.order[size_t(shape_id<triangle_set>)].size();
    CHECK(references >= n);
    // The budget is checked before each split, which may add at most its node's references.
    CHECK(double(references) <= double(options.spatial_budget) * double(n) + double(n));
    std::vector<int> seen(n, 0);
    for (uint32_t t : bvh.order[size_t(shape_id<triangle_set>)]) ++seen.at(t);
    CHECK(std::count(seen.begin(), seen.end(), 0) == 0);
    CHECK(bvh.stats.depth < 96 / 3); // the wide tree of a binary tree under 96 levels
}

// The ray's range [t0, t1] within the box, in double (empty when t0 > t1): the reference the
// walk's float slab test is checked against.
void slab_range(const ray3f& r, const box3f& b, double tmin, double tmax, double& t0, double& t1) {
    t0 = tmin;
    t1 = tmax;
    for (int a = 0; a < 3; ++a) {
        const double o = r.origin[a], d = r.dir[a], lo = b.lo[a], hi = b.hi[a];
        if (d == 0) {
            if (o < lo || o > hi) t0 = 1, t1 = 0;
            continue;
        }
        double n = (lo - o) / d, f = (hi - o) / d;
        if (n > f) std::swap(n, f);
        t0 = std::max(t0, n);
        t1 = std::min(t1, f);
    }
}

TEST_CASE("bvh: the walk enters every box the ray's range meets, ahead of the origin and behind it") {
    // The walk reduces its slab distances as integers (detail::intersect_node): exact for boxes
    // ahead of a ray with tmin >= 0, and never narrower otherwise. Boxes all around the origin,
    // rays with tmin 0.001 and with tmin -30 (so boxes behind count), infinite and short tmax:
    // every box whose range is wider than a rounding margin must reach the leaf test, and with
    // tmin >= 0 no leaf whose box's range is empty by more than that margin may (with tmin < 0
    // the test may enter boxes behind the origin that the range misses: wasted, never wrong).
    pcg32 rng = sample_rng(31, 0, 0);
    std::vector<bvh_primitive> prims;
    for (uint32_t i = 0; i < 3000; ++i) {
        box3f b = random_box(rng, 20, 1.0f);
        b.lo = b.lo - vec3f(10, 10, 10);
        b.hi = b.hi - vec3f(10, 10, 10);
        prims.push_back({b, shape_id<sphere_set>, i});
    }
    const wide_bvh bvh = build_wide_bvh(prims);
    const float inf = std::numeric_limits<float>::infinity();
    const float tmins[] = {1e-3f, -30.0f};
    const float tmaxes[] = {inf, 4.0f};
    int missed = 0, extra = 0, required = 0, rays = 0;
    for (int k = 0; k < 400; ++k) {
        ray3f r;
        r.origin = vec3f(2 * rng.next_float() - 1, 2 * rng.next_float() - 1, 2 * rng.next_float() - 1);
        vec3f d(2 * rng.next_float() - 1, 2 * rng.next_float() - 1, 2 * rng.next_float() - 1);
        if (k % 8 == 0) d.y = 0; // along a plane: the tiny-component path
        r.dir = normalize(d);
        for (float tmin : tmins)
            for (float tmax : tmaxes) {
                ++rays;
                r.tmin = tmin;
                std::vector<char> entered(prims.size(), 0);
                float t = tmax;
                traverse<false>(bvh, r, t, [&](uint32_t ref, float&) {
                    box3f leaf; // the leaf's box: its primitives' boxes together
                    for (uint32_t j = bvh_ref::first(ref); j < bvh_ref::first(ref) + bvh_ref::count(ref); ++j) {
                        const uint32_t i = bvh.order[0][j];
                        entered[i] = 1;
                        leaf.grow(prims[i].bounds.lo);
                        leaf.grow(prims[i].bounds.hi);
                    }
                    double t0, t1;
                    slab_range(r, leaf, tmin, tmax, t0, t1);
                    extra += tmin >= 0 && t0 - t1 > 1e-4 * (1 + std::fabs(t0)); // exact for tmin >= 0 only
                    return false;
                });
                for (size_t i = 0; i < prims.size(); ++i) {
                    double t0, t1;
                    slab_range(r, prims[i].bounds, tmin, tmax, t0, t1);
                    const double margin = 1e-4 * (1 + std::fabs(t1));
                    if (t1 - t0 > margin) {
                        ++required;
                        missed += !entered[i];
                    }
                }
            }
    }
    CHECK(rays == 1600);
    CHECK(required > 5000); // the test means something: rays pass several boxes each
    CHECK(missed == 0);
    CHECK(extra == 0);
}

TEST_CASE("bvh: leaf references round-trip their fields") {
    uint32_t ref = bvh_ref::make_leaf(shape_id<triangle_set>, 12345678, 16);
    CHECK(bvh_ref::is_leaf(ref));
    CHECK(bvh_ref::kind(ref) == shape_id<triangle_set>);
    CHECK(bvh_ref::first(ref) == 12345678u);
    CHECK(bvh_ref::count(ref) == 16u);
    ref = bvh_ref::make_leaf(shape_id<sphere_set>, bvh_ref::max_first, 1);
    CHECK(bvh_ref::kind(ref) == shape_id<sphere_set>);
    CHECK(bvh_ref::first(ref) == bvh_ref::max_first);
    CHECK(bvh_ref::count(ref) == 1u);
    CHECK_FALSE(bvh_ref::is_leaf(42));
    // The kind bits are as many as the list of shape kinds needs (0 is an inner node), 4 bits of
    // count below them, the first primitive in the rest: 3 kind bits and 2^25 primitives a kind
    // for up to 7 kinds.
    const uint32_t kind_bits = shape_kind_count < 8 ? 3 : 4;
    CHECK(bvh_ref::kind_bits == kind_bits);
    CHECK(bvh_ref::max_shape_kinds == (1 << kind_bits) - 1);
    CHECK(shape_kind_count <= bvh_ref::max_shape_kinds);
    CHECK(bvh_ref::max_first == (1u << (32 - kind_bits - 4)) - 1);
    // Every kind the bits can name, with the largest first and count, decodes to itself and never
    // to an inner node.
    for (uint32_t k = 0; k < uint32_t(bvh_ref::max_shape_kinds); ++k) {
        CAPTURE(k);
        uint32_t leaf = bvh_ref::make_leaf(static_cast<shape_kind>(k), bvh_ref::max_first - 15, 16);
        CHECK(bvh_ref::is_leaf(leaf));
        CHECK(uint32_t(bvh_ref::kind(leaf)) == k);
        CHECK(bvh_ref::first(leaf) == bvh_ref::max_first - 15);
        CHECK(bvh_ref::count(leaf) == 16u);
        CHECK(leaf != bvh_ref::empty);
    }
    // An inner node's reference counts 32-byte units, units_per_node to a node: the last node's reference is
    // not a leaf, names that node again, and points at its bytes; one node more would be a leaf.
    const uint32_t last = bvh_ref::node_ref(bvh_ref::max_nodes - 1);
    CHECK_FALSE(bvh_ref::is_leaf(last));
    CHECK(bvh_ref::node_index(last) == bvh_ref::max_nodes - 1);
    CHECK(uint64_t(last) * 32 == uint64_t(bvh_ref::max_nodes - 1) * sizeof(wide_node));
    CHECK(bvh_ref::is_leaf(bvh_ref::node_ref(bvh_ref::max_nodes)));
    for (uint32_t i : {0u, 1u, 2u, 1000u, 123457u})
        CHECK(bvh_ref::node_index(bvh_ref::node_ref(i)) == i);
}

} // namespace test_bvh
