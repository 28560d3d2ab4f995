#pragma once
// alias_table: draws an index i in [0, n) with probability weight_i / sum of weights, in constant
// time from one uniform number, after an O(n) build. The light sampler chooses a light in
// proportion to its power with it.
//
//   alias_table t(weights);   // non-negative, finite, at least one positive
//   uint32_t i = t.sample(u); // u uniform in [0, 1)
//   float p = t.pmf(i);       // weight_i / total: what MIS weighs the choice by
//
// Walker's alias method: every one of the n bins holds probability mass 1/n, split between its
// own index (a fraction `threshold`) and one other index, its alias. A. J. Walker, "An Efficient
// Method for Generating Discrete Random Variables with General Distributions", ACM TOMS 3(3),
// 1977. The bins are filled in O(n) by Vose's pairing of an under-full bin with an over-full one:
// M. D. Vose, "A Linear Algorithm for Generating Random Numbers with a Given Distribution", IEEE
// Transactions on Software Engineering 17(9), 1991. The over-full bin's remainder is updated as
// (q_large + q_small) - 1 rather than q_large - (1 - q_small), which keeps the rounding error
// from growing along the chain of updates (K. Schwarz, "Darts, Dice, and Coins: Sampling from a
// Discrete Distribution", 2011).
//
// Resolution of one float uniform: u carries 24 random bits (pcg32::next_float), so every
// probability sample() realises is a multiple of 2^-24. log2(n) of those bits choose the bin and
// the remaining 24 - log2(n) split it between the index and its alias: with 4096 lights, a bin's
// split is resolved to 1/4096 of the bin. An index whose pmf is below about 2^-24 (6e-8) may be
// drawn with probability 0 or 2^-24 rather than its pmf; the pmf() reported stays exact, so an
// estimator is biased only by such vanishingly unlikely lights.

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace rt {

class alias_table {
  public:
    alias_table() = default;
    // Throws std::invalid_argument when a weight is negative or not finite, when no weight is
    // positive, when the total overflows, or when there are 2^32 - 1 weights or more.
    explicit alias_table(const std::vector<double>& weights);

    // The index for the uniform u in [0, 1): bin floor(u n), then its own index or its alias by
    // the fraction of u left over. Zero-weight indices are never returned. Precondition: !empty().
    uint32_t sample(float u) const;
    // The probability of index i: weight_i / total (0 for an index out of range).
    float pmf(uint32_t i) const { return i < bins_.size() ? bins_[i].pmf : 0.0f; }
    size_t size() const { return bins_.size(); }
    bool empty() const { return bins_.empty(); }

  private:
    struct bin {
        float threshold = 1; // the fraction of the bin that is its own index; the rest is alias
        uint32_t alias = 0;
        float pmf = 0;       // weight / total, for the caller
    };
    std::vector<bin> bins_;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline alias_table::alias_table(const std::vector<double>& weights) {
    const size_t n = weights.size();
    if (n == 0) throw std::invalid_argument("alias_table: no weights");
    if (n >= UINT32_MAX) throw std::invalid_argument("alias_table: too many weights");
    double total = 0;
    for (double w : weights) {
        if (!(w >= 0) || !std::isfinite(w))
            throw std::invalid_argument("alias_table: weights must be finite and non-negative");
        total += w;
    }
    if (!(total > 0)) throw std::invalid_argument("alias_table: no positive weight");
    if (!std::isfinite(total)) throw std::invalid_argument("alias_table: the weights' total overflows");

    // q_i = n p_i: a bin's worth of mass is 1. Indices below 1 need an alias to fill their bin;
    // those above give their excess away. Both lists are used as stacks.
    bins_.resize(n);
    std::vector<double> q(n);
    std::vector<uint32_t> small, large;
    small.reserve(n);
    large.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        bins_[i].pmf = static_cast<float>(weights[i] / total);
        q[i] = weights[i] / total * static_cast<double>(n);
        (q[i] < 1 ? small : large).push_back(static_cast<uint32_t>(i));
    }
    // Vose: fill an under-full bin from an over-full index, which then has less excess and may
    // become under-full itself.
    while (!small.empty() && !large.empty()) {
        const uint32_t s = small.back(), l = large.back();
        small.pop_back();
        large.pop_back();
        bins_[s].threshold = static_cast<float>(q[s]);
        bins_[s].alias = l;
        q[l] = (q[l] + q[s]) - 1;
        (q[l] < 1 ? small : large).push_back(l);
    }
    // What remains holds (up to rounding) exactly one bin's worth each: it keeps its whole bin.
    // A zero weight can only be left over through rounding in the pairing above; it must still
    // never be drawn, so it hands its bin to the heaviest index.
    uint32_t heaviest = 0;
    for (uint32_t i = 1; i < n; ++i)
        if (weights[i] > weights[heaviest]) heaviest = i;
    for (const std::vector<uint32_t>* rest : {&small, &large})
        for (uint32_t i : *rest) {
            const bool positive = weights[i] > 0;
            bins_[i].threshold = positive ? 1.0f : 0.0f;
            bins_[i].alias = positive ? i : heaviest;
        }
}

inline uint32_t alias_table::sample(float u) const {
    const auto n = static_cast<uint32_t>(bins_.size());
    // In double, u n and its fraction are exact (u has 24 bits; exact while n < 2^29): no rounding
    // can push u n across a bin boundary or shift the split within the bin.
    const double x = static_cast<double>(u) * n;
    const double whole = std::floor(x);
    const uint32_t i = whole < n ? static_cast<uint32_t>(whole) : n - 1; // u = 1 is clamped
    const double fraction = x - static_cast<double>(i);
    const bin& b = bins_[i];
    return fraction < static_cast<double>(b.threshold) ? i : b.alias;
}

} // namespace rt
