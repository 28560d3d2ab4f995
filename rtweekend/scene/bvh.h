#pragma once
// The bounding volume hierarchy: how a ray finds the few primitives it might hit among millions.
//
//   wide_bvh build_wide_bvh(const std::vector<bvh_primitive>& prims, const bvh_build_options& = {});
//   bool traverse(const wide_bvh&, const ray3f&, float& tmax, leaf_test);   // closest or any hit
//
// The build is a binary tree split by the surface area heuristic (SAH) with binned centroids
// (Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies", IEEE RT 2007), and for
// triangles, when the caller gives their corners, also by planes through them (spatial splits,
// Stich et al. 2009: see bvh_build_options), which is then collapsed into wide nodes at least
// SAH cost (Ylitie, Karras and Laine 2017: see plan_collapse): every node holds the boxes of up to
// bvh_width children side by side, so one SIMD instruction per plane tests a ray against all of
// them (Dammertz, Hanika and Keller, "Shallow Bounding Volume Hierarchies for Fast SIMD Ray
// Tracing of Incoherent Rays", EGSR 2008; the layout Embree uses). Traversal visits the nearest
// child first and skips every child that starts beyond the closest hit found so far; an any-hit
// (shadow) query stops at the first hit.
//
// The tree knows primitives only as boxes of a shape kind (leaf_query.h). A leaf holds up to 16
// primitives of one kind, stored contiguously: `order` tells the caller in which order to lay out
// each kind's data so that a leaf is a range [first, first + count) of it (a triangle split by a
// plane is named once for each leaf that holds a part of it).
//
// A scene of a few primitives gets no nodes at all: its root is a single leaf.

#include "../core/scene_error.h"
#include "../core/force_inline.h"
#include "leaf_query.h"
#include "shape_kinds.h"
#include "../core/box3f.h"
#include "../core/vec3f.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace rt {

// Children per node: one SIMD register of float lanes for each of a node's planes, so 16 with
// AVX-512 and 8 otherwise. On the Intel Xeon of BENCHMARKS.md section 26 nodes of 16 traced mesh
// rays 11-20 % faster than nodes of 8: the same leaves under a tree one or two levels shallower,
// so fewer node loads a ray waits on. The hits are the same at either width, as ties between
// shapes are broken by index, not by the order of the walk (leaf_query.h, beats); only a user's
// shape that draws random numbers in its hit test (book 2's constant_medium) may draw others.
// A build may choose 8 with AVX-512 too (-DRTWEEKEND_BVH_WIDTH=8), to compare the two widths on
// one machine (apps/ab_compare, RTWEEKEND_AB_A_DEFINITIONS).
#if !defined(RTWEEKEND_BVH_WIDTH)
#if defined(__AVX512F__)
#define RTWEEKEND_BVH_WIDTH 16
#else
#define RTWEEKEND_BVH_WIDTH 8
#endif
#endif
#if !(RTWEEKEND_BVH_WIDTH == 8 || (RTWEEKEND_BVH_WIDTH == 16 && defined(__AVX512F__)))
#error "RTWEEKEND_BVH_WIDTH must be 8, or 16 where the compiler targets AVX-512"
#endif
inline constexpr int bvh_width = RTWEEKEND_BVH_WIDTH;

// What the builder needs to know about one primitive.
struct bvh_primitive {
    box3f bounds;
    shape_kind kind{};
    uint32_t index = 0; // the primitive's number among those of its kind
};

// A reference to a child, 32 bits: an inner node, or a leaf packed into the same bits. The top
// kind_bits bits hold 0 for an inner node, or 1 + the shape kind of a leaf: as many bits as the
// list of shape kinds needs (shape_kinds.h), 3 for up to 7 kinds, 4 for up to 15. Below them:
//   an inner node: its offset in wide_bvh::nodes in units of 32 bytes (its index times
//   units_per_node: 7 for a node of 8 children, 224 bytes; 14 for one of 16, 448 bytes), so that
//   the walk finds its address with one shift and one add; index * 224 took three instructions
//   more on the walk's critical path, node after node (BENCHMARKS.md section 25)
//   a leaf: 4 bits of its count - 1 (1..16), then its first primitive in the rest.
// With 3 kind bits, each kind may have up to 2^25 (33.5 million) primitives, and there may be up
// to 2^29 / units_per_node nodes (76.7 million of 8 children, 38.3 million of 16); each kind bit
// more halves both.
namespace bvh_ref {
inline constexpr uint32_t kind_bits = shape_kind_count < 8 ? 3 : 4;
static_assert(shape_kind_count < 16, "a leaf reference names at most 15 shape kinds");
inline constexpr uint32_t kind_shift = 32 - kind_bits;
inline constexpr int max_shape_kinds = (1 << kind_bits) - 1;
inline constexpr uint32_t max_leaf_size = 16;
inline constexpr uint32_t count_shift = kind_shift - 4;
inline constexpr uint32_t max_first = (1u << count_shift) - 1;
inline constexpr uint32_t first_leaf = 1u << kind_shift; // every reference from here up is a leaf
inline constexpr uint32_t node_unit = 32;                // bytes
// sizeof(wide_node) / node_unit: six planes and the references, a float or a reference per child
inline constexpr uint32_t units_per_node =
    uint32_t((6 * sizeof(float) + sizeof(uint32_t)) * bvh_width / node_unit);
// The last node's reference is below first_leaf.
inline constexpr uint32_t max_nodes = (first_leaf - 1) / units_per_node + 1;
inline constexpr uint32_t empty = 0xFFFFFFFFu; // the root of a tree without primitives

constexpr bool is_leaf(uint32_t ref) { return ref >= first_leaf; }
constexpr uint32_t node_ref(uint32_t index) { return index * units_per_node; }
constexpr uint32_t node_index(uint32_t ref) { return ref / units_per_node; }
constexpr shape_kind kind(uint32_t ref) { return static_cast<shape_kind>((ref >> kind_shift) - 1); }
constexpr uint32_t count(uint32_t ref) { return ((ref >> count_shift) & 15u) + 1; }
constexpr uint32_t first(uint32_t ref) { return ref & max_first; }
constexpr uint32_t make_leaf(shape_kind k, uint32_t first, uint32_t count) {
    return ((uint32_t(k) + 1) << kind_shift) | ((count - 1) << count_shift) | first;
}
} // namespace bvh_ref

// bvh_width children's boxes, coordinate by coordinate: bounds[0..2] are the low x, y, z planes
// and bounds[3..5] the high ones, bvh_width lanes each, every plane one aligned SIMD register.
// Unused slots hold empty boxes, never hit.
struct alignas(bvh_width * sizeof(float)) wide_node {
    float bounds[6][bvh_width];
    uint32_t child[bvh_width];
};
static_assert(sizeof(wide_node) == bvh_ref::units_per_node * bvh_ref::node_unit,
              "a node reference counts 32-byte units");

struct bvh_build_options {
    uint32_t max_leaf_size = 16; // at most bvh_ref::max_leaf_size
    int bins = 16;              // SAH candidate planes per axis = bins - 1
    // SAH costs, relative: visiting a node against testing one primitive. Leaves are tested
    // with SIMD, several primitives per instruction, so a primitive costs less than a node.
    float node_cost = 1.0f;
    float primitive_cost = 0.1f;
    // Spatial splits (Stich, Friedrich and Dietrich, "Spatial Splits in Bounding Volume
    // Hierarchies", HPG 2009): given the corners of the triangles (split_corners(index) for the
    // primitive of kind split_kind and that index), a node of triangles may also be split by a
    // plane through them, a triangle that straddles it going to both sides, each with the box of
    // its own part. The boxes overlap less, and a ray visits fewer nodes and tests fewer
    // triangles; a triangle is then in more than one leaf (order names it more than once).
    // Tried for nodes of more than spatial_min_count triangles where the best split by centroids
    // leaves the two boxes overlapping by more than spatial_overlap of the root's area, while the
    // references stay within spatial_budget times the primitives. The defaults: on the 75k-
    // triangle bunny's diffuse rays, 4 % fewer node visits and 2 % fewer triangle tests for a build
    // 2.6 times as long; every node (spatial_min_count 16) and the paper's overlap of 1e-5 gave
    // no fewer visits for twice that build (BENCHMARKS.md section 16).
    shape_kind split_kind{};
    std::function<std::array<vec3f, 3>(uint32_t index)> split_corners;
    uint32_t spatial_min_count = 256;
    float spatial_overlap = 1e-4f;
    float spatial_budget = 1.3f;
};

struct bvh_stats {
    size_t primitives = 0;
    size_t nodes = 0;  // inner (wide) nodes
    size_t leaves = 0;
    int depth = 0;     // of the wide tree (a root leaf has depth 0)
    double build_ms = 0;
    size_t bytes() const { return nodes * sizeof(wide_node); }
};

class wide_bvh {
  public:
    std::vector<wide_node> nodes;
    // The inner node a reference names (see bvh_ref).
    const wide_node& node(uint32_t ref) const { return node_at(nodes.data(), ref); }
    static const wide_node& node_at(const wide_node* first, uint32_t ref) {
        const char* bytes = reinterpret_cast<const char*>(first) + size_t(ref) * bvh_ref::node_unit;
        return *reinterpret_cast<const wide_node*>(bytes);
    }
    uint32_t root = bvh_ref::empty;
    // order[kind][k]: which primitive of that kind goes to position k of the kind's leaf storage
    // (with spatial splits, a triangle may go to several positions).
    std::array<std::vector<uint32_t>, shape_kind_count> order;
    bvh_stats stats;
};

wide_bvh build_wide_bvh(const std::vector<bvh_primitive>& prims, const bvh_build_options& options = {});

// Walks the tree for a ray with direction r.dir and range (r.tmin, tmax). For every leaf whose
// box the ray enters before tmax, calls leaf_test(ref, tmax) -> bool, which tests the leaf's
// primitives, lowers tmax to a closer hit and returns true if it found one. AnyHit stops at the
// first leaf that reports a hit. Returns whether any leaf did.
template <bool AnyHit, class LeafTest>
bool traverse(const wide_bvh& bvh, const ray3f& r, float& tmax, LeafTest&& leaf_test);

// Rays walked together, one per floatv lane (closest hits only): the camera rays of a batch,
// which start close together and point nearly the same way, so they enter mostly the same boxes,
// and one walk with a SIMD instruction per box and plane serves them all where each would walk
// alone (Wald, Slusallek, Benthin and Wagner, "Interactive Rendering with Coherent Ray Tracing",
// EG 2001, for packets; here over the wide tree, a box at a time for all lanes).
// bvh_packet holds lane k's ray as bvh_ray prepares it, so every lane computes the same slab
// distances its ray alone would.
struct bvh_packet {
    floatv inv[3], origin_inv[3], tmin;
    maskv negative[3];   // lanes whose ray runs down the axis: they enter a box by its high plane
    unsigned usable = 0; // lanes whose slab distances are finite (bvh_ray::usable)
    // From the count rays in `rays` (lanes from count on are ignored); bit k of dir_signs[a] is
    // the sign bit of ray k's direction on axis a (which a zero direction keeps: -0 runs down).
    // Lane by lane, the same operations as bvh_ray's, so a lane's slabs are its ray's own.
    bvh_packet(const ray_lanes& rays, const unsigned dir_signs[3], int count);
};

// Walks the tree for the lanes in `active` (bit k: lane k); tmax[k] is lane k's range, which the
// leaf tests lower. For every leaf some lane enters before its tmax, calls
// leaf_test(ref, lanes) with the bits of the lanes that enter it. The lanes that reach the
// shape a ray's own walk would find as its closest are always among them.
template <class LeafTest>
void traverse_packet(const wide_bvh& bvh, const bvh_packet& packet, float* tmax, unsigned active, LeafTest&& leaf_test);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

class bvh_builder {
  public:
    bvh_builder(const std::vector<bvh_primitive>& prims, const bvh_build_options& options)
        : options_(options), refs_(prims.size()) {
        options_.max_leaf_size = std::clamp<uint32_t>(options_.max_leaf_size, 1, bvh_ref::max_leaf_size);
        options_.bins = std::clamp(options_.bins, 2, max_bins);
        for (size_t i = 0; i < prims.size(); ++i) refs_[i] = {prims[i].bounds, prims[i].bounds.centre(), prims[i].kind, prims[i].index};
        // Spatial splits: only where a node of more than spatial_min_count triangles can exist.
        spatial_ = options_.split_corners && prims.size() > options_.spatial_min_count;
        if (spatial_) {
            box3f all;
            for (const bvh_primitive& p : prims) all.grow(p.bounds);
            min_overlap_ = options_.spatial_overlap * all.half_area();
            reference_budget_ = size_t(double(options_.spatial_budget) * double(prims.size()));
            references_ = prims.size();
            room_ = 4 * prims.size();
            // The corners, copied once: the search asks for them for every straddling reference.
            uint32_t triangles = 0;
            for (const bvh_primitive& p : prims)
                if (p.kind == options_.split_kind) triangles = std::max(triangles, p.index + 1);
            corners_.resize(triangles);
            for (uint32_t i = 0; i < triangles; ++i) corners_[i] = options_.split_corners(i);
        }
        // Depth beyond which splits fall back to the object median, which halves the count every
        // level: the binary tree stays shallower than forced_median_depth + log2(n) < 96, so the
        // traversal stack below can never overflow.
        binary_.reserve(2 * prims.size() / std::max<uint32_t>(1, options_.max_leaf_size) + 8);
    }

    wide_bvh run() {
        wide_bvh out;
        out.stats.primitives = refs_.size();
        if (refs_.empty()) return out;
        uint32_t root = build(0, uint32_t(refs_.size()), 0);
        plan_collapse();
        out.root = emit(root, out, 0);
        out.stats.nodes = out.nodes.size();
        return out;
    }

  private:
    static constexpr int W = bvh_width;
    static constexpr int max_bins = 64;
    static constexpr int forced_median_depth = 64;

    struct ref {
        box3f bounds;
        vec3f centre;
        shape_kind kind;
        uint32_t index;
    };
    struct binary_node {
        box3f bounds;
        uint32_t left = 0, right = 0; // children, for inner nodes
        uint32_t first = 0, count = 0; // range of refs_, for leaves
        bool leaf = false;
    };

    uint32_t make_leaf(const box3f& bounds, uint32_t first, uint32_t count) {
        binary_node n;
        n.bounds = bounds;
        n.first = first;
        n.count = count;
        n.leaf = true;
        binary_.push_back(n);
        return uint32_t(binary_.size() - 1);
    }

    uint32_t make_inner(const box3f& bounds, uint32_t left, uint32_t right) {
        binary_node n;
        n.bounds = bounds;
        n.left = left;
        n.right = right;
        binary_.push_back(n);
        return uint32_t(binary_.size() - 1);
    }

    // Builds the subtree over refs_[first, first + count) and returns its binary node.
    uint32_t build(uint32_t first, uint32_t count, int depth) {
        box3f bounds, centres;
        bool mixed = false;
        for (uint32_t i = first; i < first + count; ++i) {
            bounds.grow(refs_[i].bounds);
            centres.grow(refs_[i].centre);
            mixed |= refs_[i].kind != refs_[first].kind;
        }

        const float leaf_cost = options_.primitive_cost * float(count);
        if (count == 1) return make_leaf(bounds, first, count);
        box3f best_left, best_right; // the best object split's boxes, for spatial splits

        // Best binned SAH split over the three axes.
        int best_axis = -1, best_bin = 0;
        float best_cost = std::numeric_limits<float>::infinity();
        const int bins = options_.bins;
        if (depth < forced_median_depth) {
            for (int axis = 0; axis < 3; ++axis) {
                float lo = centres.lo[axis], extent = centres.hi[axis] - lo;
                // An extent so small (denormal) that bins / extent overflows has no planes to
                // offer either; an infinite scale would make 0 * inf a NaN bin below.
                const float scale = float(bins) / extent;
                if (!(extent > 0) || !std::isfinite(scale)) continue;
                box3f bin_bounds[max_bins];
                uint32_t bin_count[max_bins] = {};
                for (uint32_t i = first; i < first + count; ++i) {
                    int b = bin_of(refs_[i].centre[axis], lo, scale, bins);
                    bin_bounds[b].grow(refs_[i].bounds);
                    ++bin_count[b];
                }
                sweep_planes(bins, bin_bounds, bin_count, bin_count, [&](int b, float cost, const box3f& left) {
                    if (!(cost < best_cost)) return;
                    best_cost = cost;
                    best_axis = axis;
                    best_bin = b;
                    if (spatial_) {
                        best_left = left;
                        best_right = box3f();
                        for (int k = b + 1; k < bins; ++k) best_right.grow(bin_bounds[k]);
                    }
                });
            }
        }
        float parent_area = bounds.half_area();
        float split_cost = best_axis >= 0 && parent_area > 0
                               ? options_.node_cost + options_.primitive_cost * best_cost / parent_area
                               : std::numeric_limits<float>::infinity();
        // A split through the triangles, where the split by centroids leaves boxes that overlap.
        spatial_split spatial;
        // The references made (copies of split triangles) and the room refs_ takes (a split
        // appends its right side) both stay bounded: the work and memory of a build are O(n).
        const bool may_split_spatially = spatial_ && count > options_.spatial_min_count && !mixed &&
                                         refs_[first].kind == options_.split_kind && depth < forced_median_depth &&
                                         references_ < reference_budget_ && refs_.size() + count <= room_;
        if (may_split_spatially && parent_area > 0 &&
            (best_axis < 0 || overlap_area(best_left, best_right) > min_overlap_)) {
            spatial = find_spatial_split(first, count, bounds);
            const float cost = options_.node_cost + options_.primitive_cost * spatial.cost / parent_area;
            if (spatial.axis >= 0 && cost < split_cost && cost < leaf_cost) {
                split_cost = cost;
            } else {
                spatial.axis = -1;
            }
        }

        if (count <= options_.max_leaf_size && leaf_cost <= split_cost) {
            if (!mixed) return make_leaf(bounds, first, count);
            // A leaf holds one kind: split the range by kind instead.
            const shape_kind first_kind = refs_[first].kind;
            auto middle = std::partition(refs_.begin() + first, refs_.begin() + first + count,
                                         [&](const ref& r) { return r.kind == first_kind; });
            return split_at(first, count, uint32_t(middle - refs_.begin()), bounds, depth);
        }

        if (spatial.axis >= 0) return split_spatially(first, count, spatial, bounds, depth);
        uint32_t middle;
        if (best_axis >= 0) {
            float lo = centres.lo[best_axis], scale = float(bins) / (centres.hi[best_axis] - lo);
            auto it = std::partition(refs_.begin() + first, refs_.begin() + first + count, [&](const ref& r) {
                return bin_of(r.centre[best_axis], lo, scale, bins) <= best_bin;
            });
            middle = uint32_t(it - refs_.begin());
        } else {
            // No plane separates the centres (all equal), or the tree is already deep: split at
            // the object median of the widest centre axis.
            vec3f e = centres.hi - centres.lo;
            int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
            middle = first + count / 2;
            std::nth_element(refs_.begin() + first, refs_.begin() + middle, refs_.begin() + first + count,
                             [axis](const ref& a, const ref& b) { return a.centre[axis] < b.centre[axis]; });
        }
        if (middle == first || middle == first + count) middle = first + count / 2;
        return split_at(first, count, middle, bounds, depth);
    }

    // The SAH cost of every plane between bins b and b + 1 with references on both sides: the
    // area of the box of the bins left of it times the references there, plus the same right of
    // it; candidate(b, cost, left box) hears each. A split by centroids counts a reference in its
    // bin on both sides (left_counts = right_counts); a spatial split in the bin where it enters
    // for the left and where it leaves for the right.
    template <class Candidate>
    static void sweep_planes(int bins, const box3f* bin_bounds, const uint32_t* left_counts,
                             const uint32_t* right_counts, Candidate&& candidate) {
        float right_area[max_bins];
        uint32_t right_count[max_bins];
        box3f acc;
        uint32_t n = 0;
        for (int b = bins - 1; b > 0; --b) { // from the right: what lies right of every plane
            acc.grow(bin_bounds[b]);
            n += right_counts[b];
            right_area[b] = acc.half_area();
            right_count[b] = n;
        }
        acc = box3f();
        n = 0;
        for (int b = 0; b < bins - 1; ++b) {
            acc.grow(bin_bounds[b]);
            n += left_counts[b];
            if (n == 0 || right_count[b + 1] == 0) continue;
            candidate(b, acc.half_area() * float(n) + right_area[b + 1] * float(right_count[b + 1]), acc);
        }
    }

    struct spatial_split {
        int axis = -1;
        float plane = 0;
        float cost = std::numeric_limits<float>::infinity(); // SAH, areas times counts
    };

    static float overlap_area(box3f a, const box3f& b) {
        a.clip(b);
        return a.half_area();
    }

    // The boxes of the parts of triangle v on either side of the plane x[axis] = plane, within
    // `within` (the reference's box so far). Where an edge crosses the plane, the point is
    // computed in double and the boxes widened past it by more than that computation's error and
    // the rounding to float (2^-22 of the point, 2^-50 of the edge's ends), so that each box holds
    // every point of its part: a ray that hits the triangle there enters the box.
    static void split_box(const std::array<vec3f, 3>& v, int axis, float plane, const box3f within, box3f& left,
                          box3f& right) {
        left = right = box3f();
        auto widened = [](double x, double a, double b, double side) {
            return float(x + side * (std::fabs(x) * 0x1p-22 + (std::fabs(a) + std::fabs(b)) * 0x1p-50));
        };
        for (int e = 0; e < 3; ++e) {
            const vec3f& a = v[size_t(e)];
            const vec3f& b = v[size_t((e + 1) % 3)];
            const float ca = a[axis], cb = b[axis];
            if (ca <= plane) left.grow(a);
            if (ca >= plane) right.grow(a);
            if (!((ca < plane && cb > plane) || (ca > plane && cb < plane))) continue;
            const double s = (double(plane) - ca) / (double(cb) - ca);
            const double x = a.x + s * (double(b.x) - a.x), y = a.y + s * (double(b.y) - a.y),
                         z = a.z + s * (double(b.z) - a.z);
            const vec3f lo(widened(x, a.x, b.x, -1), widened(y, a.y, b.y, -1), widened(z, a.z, b.z, -1));
            const vec3f hi(widened(x, a.x, b.x, +1), widened(y, a.y, b.y, +1), widened(z, a.z, b.z, +1));
            left.grow(lo), left.grow(hi), right.grow(lo), right.grow(hi);
        }
        // Within the reference's box, and each on its side of the plane (the crossings were
        // widened past it).
        auto component = [axis](vec3f& p) -> float& { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); };
        left.clip(within);
        right.clip(within);
        component(left.hi) = fmin_inline(component(left.hi), plane);
        component(right.lo) = fmax_inline(component(right.lo), plane);
    }

    // The best plane through the triangles of refs_[first, first + count): binned over the
    // node's box, each reference cut into the bins it spans.
    spatial_split find_spatial_split(uint32_t first, uint32_t count, const box3f& bounds) const {
        spatial_split best;
        const int bins = options_.bins;
        for (int axis = 0; axis < 3; ++axis) {
            const float lo = bounds.lo[axis], extent = bounds.hi[axis] - lo;
            const float width = extent / float(bins);
            if (!(width > 0) || !std::isfinite(float(bins) / extent)) continue;
            auto plane = [&](int b) { return b == bins ? bounds.hi[axis] : lo + width * float(b); };
            box3f bin_bounds[max_bins];
            uint32_t entering[max_bins] = {}, leaving[max_bins] = {};
            for (uint32_t i = first; i < first + count; ++i) {
                const ref& r = refs_[i];
                int b0 = bin_of(r.bounds.lo[axis], lo, float(bins) / extent, bins);
                int b1 = bin_of(r.bounds.hi[axis], lo, float(bins) / extent, bins);
                // A bin's planes are rounded: the reference enters the bin whose slab holds it.
                while (b0 > 0 && r.bounds.lo[axis] < plane(b0)) --b0;
                while (b1 < bins - 1 && r.bounds.hi[axis] > plane(b1 + 1)) ++b1;
                b1 = std::max(b0, b1);
                ++entering[b0];
                ++leaving[b1];
                if (b0 == b1) {
                    bin_bounds[b0].grow(r.bounds);
                    continue;
                }
                // Cut at each plane in turn: the part left of it fills the bin, the rest goes on.
                const std::array<vec3f, 3>& corners = corners_[r.index];
                box3f rest = r.bounds, part;
                for (int b = b0; b < b1; ++b) {
                    split_box(corners, axis, plane(b + 1), rest, part, rest);
                    bin_bounds[b].grow(part);
                }
                bin_bounds[b1].grow(rest);
            }
            sweep_planes(bins, bin_bounds, entering, leaving, [&](int b, float cost, const box3f&) {
                if (cost < best.cost) best = {axis, plane(b + 1), cost};
            });
        }
        return best;
    }

    // Splits refs_[first, first + count) by the plane: a reference on one side goes there, one
    // across it to both, each part with its clipped box. The left ones stay in place (they are
    // never more than count), the right ones are appended to refs_.
    uint32_t split_spatially(uint32_t first, uint32_t count, const spatial_split& split, const box3f& bounds,
                             int depth) {
        const int axis = split.axis;
        std::vector<ref> left, right;
        left.reserve(count);
        right.reserve(count);
        for (uint32_t i = first; i < first + count; ++i) {
            const ref& r = refs_[i];
            if (r.bounds.hi[axis] <= split.plane) {
                left.push_back(r);
            } else if (r.bounds.lo[axis] >= split.plane) {
                right.push_back(r);
            } else {
                ref l = r, rr = r;
                split_box(corners_[r.index], axis, split.plane, r.bounds, l.bounds, rr.bounds);
                const bool to_left = !l.bounds.empty(), to_right = !rr.bounds.empty();
                if (to_left) left.push_back({l.bounds, l.bounds.centre(), l.kind, l.index});
                if (to_right) right.push_back({rr.bounds, rr.bounds.centre(), rr.kind, rr.index});
                if (!to_left && !to_right) left.push_back(r); // cannot happen; never lose a triangle
                if (to_left && to_right) ++references_;
            }
        }
        if (left.empty() || right.empty()) { // rounding left nothing on one side: split by count
            const uint32_t middle = first + count / 2;
            return split_at(first, count, middle, bounds, depth);
        }
        std::copy(left.begin(), left.end(), refs_.begin() + first);
        const auto right_first = uint32_t(refs_.size());
        refs_.insert(refs_.end(), right.begin(), right.end());
        const uint32_t l = build(first, uint32_t(left.size()), depth + 1);
        const uint32_t r = build(right_first, uint32_t(right.size()), depth + 1);
        return make_inner(bounds, l, r);
    }

    uint32_t split_at(uint32_t first, uint32_t count, uint32_t middle, const box3f& bounds, int depth) {
        uint32_t left = build(first, middle - first, depth + 1);
        uint32_t right = build(middle, first + count - middle, depth + 1);
        return make_inner(bounds, left, right);
    }

    // A plane within 1e-30 of zero moves out to +-1e-30 (the box only grows). A denormal plane,
    // which a box rounded outwards from 0 would otherwise get, makes every slab test of the node
    // take a floating-point microcode assist: over a hundred cycles on x86.
    static float away_from_tiny(float x, int direction) {
        constexpr float tiny = 1e-30f;
        return std::fabs(x) < tiny ? float(direction) * tiny : x;
    }

    static int bin_of(float c, float lo, float scale, int bins) {
        int b = int((c - lo) * scale);
        return std::clamp(b, 0, bins - 1);
    }

    // Which binary nodes become the wide tree's nodes: the collapse of least SAH cost, by
    // dynamic programming over the binary tree (Ylitie, Karras and Laine, "Efficient Incoherent
    // Ray Traversal on GPUs Through Compressed Wide BVHs", HPG 2017, section 3.1, with the leaves
    // kept as the binary build made them). cost(b, i) is the least cost of binary node b's
    // subtree given at most i slots of its wide parent: a leaf costs its primitives; an inner
    // node in one slot is a wide node of its own (its area times node_cost, plus its two
    // children sharing bvh_width slots); given more slots it may instead hand them to its
    // children. Opening the largest inner child until there are bvh_width is one such collapse,
    // so this one costs at most as much.
    float& cost(uint32_t b, int slots) { return cost_[size_t(b) * W + size_t(slots - 1)]; }

    // The slots (1 .. slots - 1) for inner node b's left child, the rest for its right, that
    // cost least; cost_of_split gets that cost.
    int best_split(uint32_t b, int slots, float* cost_of_split = nullptr) {
        const binary_node& n = binary_[b];
        int best = 1;
        float best_cost = std::numeric_limits<float>::infinity();
        for (int k = 1; k < slots; ++k) {
            const float c = cost(n.left, k) + cost(n.right, slots - k);
            if (c < best_cost) {
                best_cost = c;
                best = k;
            }
        }
        if (cost_of_split) *cost_of_split = best_cost;
        return best;
    }

    void plan_collapse() {
        cost_.assign(binary_.size() * W, 0.0f);
        // Children precede their parents in binary_ (make_inner comes after both are built).
        for (uint32_t b = 0; b < binary_.size(); ++b) {
            const binary_node& n = binary_[b];
            if (n.leaf) {
                const float c = n.bounds.half_area() * options_.primitive_cost * float(n.count);
                for (int i = 1; i <= W; ++i) cost(b, i) = c;
                continue;
            }
            float split[W + 1]; // split[i]: the best sharing of i slots between the two children
            for (int i = 2; i <= W; ++i) best_split(b, i, &split[i]);
            cost(b, 1) = n.bounds.half_area() * options_.node_cost + split[W];
            for (int i = 2; i <= W; ++i) cost(b, i) = std::min(cost(b, i - 1), split[i]);
        }
    }

    // Appends the subtrees that binary node b's share of `slots` slots holds, as plan_collapse
    // costed them: b itself (a leaf, or an inner node that gets a wide node), or its
    // children's subtrees.
    void collect(uint32_t b, int slots, uint32_t* children, int& n) {
        if (binary_[b].leaf || slots == 1) {
            children[n++] = b;
            return;
        }
        float split = 0;
        const int k = best_split(b, slots, &split);
        if (!(split < cost(b, slots - 1))) {
            collect(b, slots - 1, children, n);
            return;
        }
        collect(binary_[b].left, k, children, n);
        collect(binary_[b].right, slots - k, children, n);
    }

    // Writes the wide subtree for binary node b and returns the reference to it.
    uint32_t emit(uint32_t b, wide_bvh& out, int depth) {
        const binary_node& node = binary_[b];
        out.stats.depth = std::max(out.stats.depth, depth);
        if (node.leaf) {
            ++out.stats.leaves;
            shape_kind kind = refs_[node.first].kind;
            auto& order = out.order[size_t(kind)];
            if (order.size() + node.count > size_t(bvh_ref::max_first) + 1)
                throw scene_error("too many shapes of one kind for the BVH (at most " +
                                  std::to_string(size_t(bvh_ref::max_first) + 1) + ")");
            auto first = uint32_t(order.size());
            for (uint32_t i = node.first; i < node.first + node.count; ++i) order.push_back(refs_[i].index);
            return bvh_ref::make_leaf(kind, first, node.count);
        }
        // Its children: the binary subtrees plan_collapse chose for its bvh_width slots.
        uint32_t children[W];
        int n = 0;
        const int k = best_split(b, W);
        collect(node.left, k, children, n);
        collect(node.right, W - k, children, n);
        if (out.nodes.size() >= bvh_ref::max_nodes) throw scene_error("too many BVH nodes (at most " + std::to_string(bvh_ref::max_nodes) + ")");
        auto index = uint32_t(out.nodes.size());
        out.nodes.emplace_back();
        wide_node filled;
        for (int i = 0; i < W; ++i) {
            box3f box; // empty for unused slots
            uint32_t child = bvh_ref::empty;
            if (i < n) {
                box = binary_[children[i]].bounds;
                child = emit(children[i], out, depth + 1);
            }
            filled.bounds[0][i] = away_from_tiny(box.lo.x, -1);
            filled.bounds[1][i] = away_from_tiny(box.lo.y, -1);
            filled.bounds[2][i] = away_from_tiny(box.lo.z, -1);
            filled.bounds[3][i] = away_from_tiny(box.hi.x, +1);
            filled.bounds[4][i] = away_from_tiny(box.hi.y, +1);
            filled.bounds[5][i] = away_from_tiny(box.hi.z, +1);
            filled.child[i] = child;
        }
        out.nodes[index] = filled;
        return bvh_ref::node_ref(index);
    }

    bvh_build_options options_;
    std::vector<ref> refs_;
    std::vector<binary_node> binary_;
    std::vector<float> cost_; // plan_collapse's cost(b, slots), bvh_width per binary node
    // Spatial splits: whether they are tried, the triangles' corners, the overlap below which a
    // split by centroids is good enough, and the references made so far (a triangle split in two
    // counts twice) against their budget.
    bool spatial_ = false;
    std::vector<std::array<vec3f, 3>> corners_;
    float min_overlap_ = 0;
    size_t references_ = 0, reference_budget_ = 0, room_ = 0;
};

// The ray, prepared for box tests: t = (plane - origin) / dir as plane * inv - origin * inv.
// `usable` is false for a ray whose slab distances are not finite (a NaN component, or an origin
// so far out that origin / direction overflows, as a shadow ray offset by 1e23 had): it hits
// nothing, since the slab test would otherwise find +inf <= +inf in the empty slots of a node and
// follow them (an XML scene with ShadowRayEpsilon 1e20 crashed render). Built once per ray, with
// the three axes in one SIMD register where there is one: one division instead of three, and no
// branch per axis.
struct bvh_ray {
    float inv[4], origin_inv[4];
    int near_plane[3], far_plane[3]; // which of bounds[0..5] is entered first on each axis
    float tmin;
    bool usable;

    explicit bvh_ray(const ray3f& r) : tmin(r.tmin) {
#if defined(__SSE2__)
        // A zero component would give 0 * inf = NaN for a plane through the origin; a tiny one
        // gives huge but finite slab distances, which compare correctly.
        const __m128 d = _mm_set_ps(0.0f, r.dir.z, r.dir.y, r.dir.x);
        const __m128 sign = _mm_and_ps(d, _mm_set1_ps(-0.0f));
        const __m128 tiny = _mm_cmplt_ps(_mm_andnot_ps(_mm_set1_ps(-0.0f), d), _mm_set1_ps(1e-20f));
        const __m128 safe = _mm_or_ps(_mm_andnot_ps(tiny, d), _mm_and_ps(tiny, _mm_or_ps(sign, _mm_set1_ps(1e-20f))));
        const __m128 inv_v = _mm_div_ps(_mm_set1_ps(1.0f), safe);
        const __m128 oi = _mm_mul_ps(_mm_set_ps(0.0f, r.origin.z, r.origin.y, r.origin.x), inv_v);
        _mm_storeu_ps(inv, inv_v);
        _mm_storeu_ps(origin_inv, oi);
        const __m128 limit = _mm_set1_ps(std::numeric_limits<float>::max());
        const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
        const int finite = _mm_movemask_ps(_mm_and_ps(_mm_cmple_ps(_mm_and_ps(inv_v, abs_mask), limit),
                                                      _mm_cmple_ps(_mm_and_ps(oi, abs_mask), limit)));
        usable = (finite & 7) == 7;
        const int negative = _mm_movemask_ps(d);
        RTWEEKEND_UNROLL(3)
        for (int a = 0; a < 3; ++a) {
            const int n = (negative >> a) & 1;
            near_plane[a] = a + 3 * n;
            far_plane[a] = a + 3 - 3 * n;
        }
#else
        usable = true;
        for (int a = 0; a < 3; ++a) {
            float d = r.dir[a];
            if (std::fabs(d) < 1e-20f) d = std::copysign(1e-20f, d); // see above
            inv[a] = 1.0f / d;
            origin_inv[a] = r.origin[a] * inv[a];
            usable = usable && std::isfinite(inv[a]) && std::isfinite(origin_inv[a]);
            int negative = int(std::signbit(d));
            near_plane[a] = a + 3 * negative;
            far_plane[a] = a + 3 - 3 * negative;
        }
#endif
    }
};

// Far distances are widened by a few ulps so that rounding never makes a ray that grazes a box
// miss it: a lost box would lose every primitive in it (Ize, "Robust BVH Ray Traversal", JCGT
// 2013, bounds the error at 1 + 2 gamma_3; this factor covers it with room to spare).
inline constexpr float bvh_far_scale = 1.0f + 8.0f * std::numeric_limits<float>::epsilon();

// Tests the ray against a node's boxes: one bit per child entered before tmax, and each
// child's entry distance.
//
// With AVX2 the walk's critical path (node load, slab distances, the two reductions, the
// comparison, the next node's address) is shortened by doing the reductions, the widening and the
// comparison in integer instructions of one cycle each, not in floating-point ones of four on
// recent Intel cores (two on AMD's). On the Intel Xeon that took mesh diffuse rays from 0.87 to
// 0.96 of Embree's speed (BENCHMARKS.md section 22).
//   - A float's bits read as a signed integer order non-negative floats as the floats, and put
//     every negative float below every non-negative one. So an integer max over a set holding a
//     non-negative value is the float max, and over a set of negatives is at most the float max;
//     an integer min over non-negatives is the float min, and over a set with a negative is a
//     negative at least the float min. The entry distance never comes out larger, nor the exit
//     distance smaller: a box is never lost. With tmin >= 0 (every ray the renderer traces) the
//     entry distance is exact, and so is the verdict.
//   - Then adding 16 to the exit distance's bits raises it by 16 ulps, at least bvh_far_scale's
//     8 epsilon relative (an ulp is at least half an epsilon of the value), and the comparison is
//     of integers too, exact for an entry distance >= 0. An exit at +inf (an infinite box) reads
//     as above every finite value, one at -inf (an empty slot) as negative: entered and not.
//   - A ray with tmin < 0 compares the reduced distances as floats, widened by bvh_far_scale.
inline unsigned intersect_node(const wide_node& node, const bvh_ray& r, float tmax, float* tnear_out) {
#if RTWEEKEND_BVH_WIDTH == 16
    // Sixteen boxes, one 512-bit register a plane; the same steps as the AVX2 test below.
    static_assert(bvh_width == 16, "the AVX-512 test is of sixteen boxes");
    auto plane = [&](int p, int a) {
        return _mm512_castps_si512(
            _mm512_fmsub_ps(_mm512_load_ps(node.bounds[p]), _mm512_set1_ps(r.inv[a]), _mm512_set1_ps(r.origin_inv[a])));
    };
    // The masked forms with every lane kept are the plain instructions; g++ 12's unmasked ones
    // start from an "undefined" register that -Wmaybe-uninitialized reports (GCC bug 105593).
    auto imax = [](__m512i a, __m512i b) { return _mm512_mask_max_epi32(a, 0xFFFF, a, b); };
    auto imin = [](__m512i a, __m512i b) { return _mm512_mask_min_epi32(a, 0xFFFF, a, b); };
    const __m512i tnear = imax(imax(plane(r.near_plane[0], 0), plane(r.near_plane[1], 1)),
                               imax(plane(r.near_plane[2], 2), _mm512_castps_si512(_mm512_set1_ps(r.tmin))));
    const __m512i tfar = imin(imin(plane(r.far_plane[0], 0), plane(r.far_plane[1], 1)),
                              imin(plane(r.far_plane[2], 2), _mm512_castps_si512(_mm512_set1_ps(tmax))));
    _mm512_storeu_si512(tnear_out, tnear);
    if (r.tmin >= 0) return unsigned(_mm512_cmple_epi32_mask(tnear, _mm512_add_epi32(tfar, _mm512_set1_epi32(16))));
    const __m512 far_widened = _mm512_mul_ps(_mm512_castsi512_ps(tfar), _mm512_set1_ps(bvh_far_scale));
    return unsigned(_mm512_cmp_ps_mask(_mm512_castsi512_ps(tnear), far_widened, _CMP_LE_OQ));
#elif defined(__AVX__)
    static_assert(bvh_width == 8, "the AVX test is of eight boxes, one 256-bit register a plane");
    auto plane = [&](int p, int a) {
        __m256 b = _mm256_load_ps(node.bounds[p]);
#if defined(__FMA__)
        return _mm256_fmsub_ps(b, _mm256_set1_ps(r.inv[a]), _mm256_set1_ps(r.origin_inv[a]));
#else
        return _mm256_sub_ps(_mm256_mul_ps(b, _mm256_set1_ps(r.inv[a])), _mm256_set1_ps(r.origin_inv[a]));
#endif
    };
#if defined(__AVX2__)
    auto as_int = [](__m256 x) { return _mm256_castps_si256(x); }; // the same bits
    const __m256i tnear = _mm256_max_epi32(_mm256_max_epi32(as_int(plane(r.near_plane[0], 0)), as_int(plane(r.near_plane[1], 1))),
                                           _mm256_max_epi32(as_int(plane(r.near_plane[2], 2)), as_int(_mm256_set1_ps(r.tmin))));
    const __m256i tfar = _mm256_min_epi32(_mm256_min_epi32(as_int(plane(r.far_plane[0], 0)), as_int(plane(r.far_plane[1], 1))),
                                          _mm256_min_epi32(as_int(plane(r.far_plane[2], 2)), as_int(_mm256_set1_ps(tmax))));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(tnear_out), tnear);
    if (r.tmin >= 0) {
#if defined(__AVX512VL__)
        // Into a mask register: one instruction for the three below (BENCHMARKS.md section 25).
        return unsigned(_mm256_cmple_epi32_mask(tnear, _mm256_add_epi32(tfar, _mm256_set1_epi32(16))));
#else
        const __m256i beyond = _mm256_cmpgt_epi32(tnear, _mm256_add_epi32(tfar, _mm256_set1_epi32(16)));
        return unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(beyond))) ^ 0xFFu;
#endif
    }
    const __m256 far_widened = _mm256_mul_ps(_mm256_castsi256_ps(tfar), _mm256_set1_ps(bvh_far_scale));
    return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(_mm256_castsi256_ps(tnear), far_widened, _CMP_LE_OQ)));
#else
    __m256 tnear = _mm256_max_ps(_mm256_max_ps(plane(r.near_plane[0], 0), plane(r.near_plane[1], 1)),
                                 _mm256_max_ps(plane(r.near_plane[2], 2), _mm256_set1_ps(r.tmin)));
    __m256 tfar = _mm256_min_ps(_mm256_min_ps(plane(r.far_plane[0], 0), plane(r.far_plane[1], 1)),
                                _mm256_min_ps(plane(r.far_plane[2], 2), _mm256_set1_ps(tmax)));
    tfar = _mm256_mul_ps(tfar, _mm256_set1_ps(bvh_far_scale));
    _mm256_storeu_ps(tnear_out, tnear);
    return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(tnear, tfar, _CMP_LE_OQ)));
#endif
#else
    unsigned mask = 0;
    for (int i = 0; i < bvh_width; ++i) {
        float tn = r.tmin, tf = tmax;
        for (int a = 0; a < 3; ++a) {
            tn = fmax_inline(tn, node.bounds[r.near_plane[a]][i] * r.inv[a] - r.origin_inv[a]);
            tf = fmin_inline(tf, node.bounds[r.far_plane[a]][i] * r.inv[a] - r.origin_inv[a]);
        }
        tnear_out[i] = tn;
        if (tn <= tf * bvh_far_scale) mask |= 1u << i;
    }
    return mask;
#endif
}

} // namespace detail

inline wide_bvh build_wide_bvh(const std::vector<bvh_primitive>& prims, const bvh_build_options& options) {
    auto start = std::chrono::steady_clock::now();
    wide_bvh out = detail::bvh_builder(prims, options).run();
    out.stats.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

template <bool AnyHit, class LeafTest>
bool traverse(const wide_bvh& bvh, const ray3f& r, float& tmax, LeafTest&& leaf_test) {
    if (bvh.root == bvh_ref::empty) return false;
    if (bvh_ref::is_leaf(bvh.root)) return leaf_test(bvh.root, tmax);

    const detail::bvh_ray ray(r);
    if (!ray.usable) return false; // a ray whose slab distances are not finite: see bvh_ray
    // Held here rather than read from bvh at every node: the leaf test is a call the compiler
    // cannot see through, after which it would read the array's address again.
    const wide_node* const nodes = bvh.nodes.data();
    struct entry {
        uint32_t ref;
        float tnear;
    };
    // Depth < 96 (see bvh_builder) and at most bvh_width - 1 entries pushed per level.
    entry stack[(bvh_width - 1) * 96 + bvh_width];
    int top = 0;
    bool found = false;
    uint32_t ref = bvh.root;
    for (;;) {
        if (!bvh_ref::is_leaf(ref)) {
            alignas(64) float tnear[bvh_width];
            const wide_node& node = wide_bvh::node_at(nodes, ref);
            unsigned mask = detail::intersect_node(node, ray, tmax, tnear);
            const uint32_t* child = node.child;
            if (mask != 0) {
                int first = __builtin_ctz(mask);
                mask &= mask - 1;
                if (mask == 0) { // one child entered: go straight on
                    ref = child[first];
                    continue;
                }
                if (AnyHit) {
                    // Any hit ends the walk, so order matters little: no sorting, the rest wait.
                    for (; mask; mask &= mask - 1) {
                        int i = __builtin_ctz(mask);
                        stack[top++] = {child[i], tnear[i]};
                    }
                    ref = child[first];
                    continue;
                }
                int second = __builtin_ctz(mask);
                mask &= mask - 1;
                if (mask == 0) { // two, the usual case of several: no loops, the compiler can use cmov
                    bool swap = tnear[second] < tnear[first];
                    int near = swap ? second : first, far = swap ? first : second;
                    stack[top++] = {child[far], tnear[far]};
                    ref = child[near];
                    continue;
                }
                // Three or more: sorted in place on the stack, farthest deepest; go on with the
                // nearest.
                mask |= 1u << second;
                entry* hits = stack + top;
                int n = 0;
                hits[n++] = {child[first], tnear[first]};
                while (mask) {
                    int i = __builtin_ctz(mask);
                    mask &= mask - 1;
                    entry e{child[i], tnear[i]};
                    int k = n++;
                    while (k > 0 && hits[k - 1].tnear < e.tnear) { // descending by distance
                        hits[k] = hits[k - 1];
                        --k;
                    }
                    hits[k] = e;
                }
                top += n - 1;
                ref = hits[n - 1].ref;
                continue;
            }
        } else if (leaf_test(ref, tmax)) {
            found = true;
            if (AnyHit) return true;
        }
        // Next: the nearest pending child that still starts before the closest hit (an any-hit
        // walk's tmax never shrinks: every pending child still qualifies).
        if (AnyHit) {
            if (top == 0) return found;
            ref = stack[--top].ref;
            continue;
        }
        for (;;) {
            if (top == 0) return found;
            const entry& e = stack[--top];
            if (e.tnear <= tmax) {
                ref = e.ref;
                break;
            }
        }
    }
}


inline bvh_packet::bvh_packet(const ray_lanes& rays, const unsigned dir_signs[3], int count) {
    const floatv origin[3] = {rays.ox, rays.oy, rays.oz}, dir[3] = {rays.dx, rays.dy, rays.dz};
    const floatv tiny(1e-20f), largest(std::numeric_limits<float>::max());
    maskv finite = first_lanes(unsigned(count));
    RTWEEKEND_UNROLL(3)
    for (int a = 0; a < 3; ++a) {
        // A component below 1e-20 in size becomes 1e-20 of its sign (bvh_ray says why).
        const maskv is_tiny = (dir[a] < tiny) & (dir[a] > -tiny);
        const floatv safe = select(is_tiny, select(lanes_of(dir_signs[a]), -tiny, tiny), dir[a]);
        inv[a] = floatv(1.0f) / safe;
        origin_inv[a] = origin[a] * inv[a];
        negative[a] = inv[a] < floatv(0.0f);
        finite = finite & (inv[a] <= largest) & (inv[a] >= -largest) & (origin_inv[a] <= largest) &
                 (origin_inv[a] >= -largest);
    }
    usable = bits(finite);
    tmin = rays.tmin;
}

template <class LeafTest>
void traverse_packet(const wide_bvh& bvh, const bvh_packet& packet, float* tmax, unsigned active, LeafTest&& leaf_test) {
    active &= packet.usable;
    if (bvh.root == bvh_ref::empty || active == 0) return;
    if (bvh_ref::is_leaf(bvh.root)) {
        leaf_test(bvh.root, active);
        return;
    }
    // A child some lane entered: its lanes and their entry distances.
    struct entry {
        floatv tnear;
        uint32_t ref;
        unsigned lanes;
    };
    // Depth < 96 (see bvh_builder) and at most bvh_width - 1 entries pushed per level.
    entry stack[(bvh_width - 1) * 96 + bvh_width];
    int top = 0;
    uint32_t ref = bvh.root;
    unsigned lanes = active;
    const floatv infinity(std::numeric_limits<float>::infinity());
    for (;;) {
        if (!bvh_ref::is_leaf(ref)) {
            const wide_node& node = bvh.node(ref);
            const floatv far_limit = floatv::load(tmax);
            entry entered[bvh_width];
            float order[bvh_width];
            // First the bvh_width tests, into a mask of the children entered; then only those. A
            // branch on each child's test was mispredicted often (which children a packet
            // enters is the scene's business); this walk's one branch per entered child ends
            // its loop once.
            floatv child_tnear[bvh_width];
            unsigned child_lanes[bvh_width];
            unsigned children = 0;
            for (int c = 0; c < bvh_width; ++c) {
                // The slab test of a ray's own walk (detail::intersect_node), lane by lane: each
                // lane's near plane on an axis picked by its direction's sign, as bvh_ray picks it
                // (so an empty slot, low planes +inf and high ones -inf, is entered by no lane).
                floatv near_t[3], far_t[3];
                RTWEEKEND_UNROLL(3)
                for (int a = 0; a < 3; ++a) {
                    const floatv lo = fmsub(floatv(node.bounds[a][c]), packet.inv[a], packet.origin_inv[a]);
                    const floatv hi = fmsub(floatv(node.bounds[a + 3][c]), packet.inv[a], packet.origin_inv[a]);
                    near_t[a] = select(packet.negative[a], hi, lo);
                    far_t[a] = select(packet.negative[a], lo, hi);
                }
                const floatv tnear = max(max(near_t[0], near_t[1]), max(near_t[2], packet.tmin));
                floatv tfar = min(min(far_t[0], far_t[1]), min(far_t[2], far_limit));
                tfar = tfar * floatv(detail::bvh_far_scale);
                child_tnear[c] = tnear;
                child_lanes[c] = bits(tnear <= tfar) & lanes;
                children |= unsigned(child_lanes[c] != 0) << c;
            }
            int n = 0;
            for (unsigned m = children; m != 0; m &= m - 1, ++n) {
                const int c = __builtin_ctz(m);
                // n itself (n < bvh_width, a power of 2), as the compiler cannot tell
                const int slot = n & (bvh_width - 1);
                entered[slot] = {child_tnear[c], node.child[c], child_lanes[c]};
                order[slot] = reduce_min(select(lanes_of(child_lanes[c]), child_tnear[c], infinity)); // its nearest lane's entry
            }
            if (n > 0) {
                // Nearest child first; the others wait on the stack, farthest deepest.
                for (int i = 1; i < n; ++i)
                    for (int k = i; k > 0 && order[k] < order[k - 1]; --k) {
                        std::swap(order[k], order[k - 1]);
                        std::swap(entered[k], entered[k - 1]);
                    }
                for (int i = n - 1; i > 0; --i) stack[top++] = entered[i];
                ref = entered[0].ref;
                lanes = entered[0].lanes;
                continue;
            }
        } else {
            leaf_test(ref, lanes);
        }
        // Next: the nearest pending child with lanes that still enter it before their tmax.
        for (;;) {
            if (top == 0) return;
            const entry& e = stack[--top];
            lanes = e.lanes & bits(e.tnear <= floatv::load(tmax));
            if (lanes != 0) {
                ref = e.ref;
                break;
            }
        }
    }
}

} // namespace rt
