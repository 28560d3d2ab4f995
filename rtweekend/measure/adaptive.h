#pragma once
// Adaptive sampling's plan (camera::adaptive_error): which pixel takes how many samples, in
// rounds over the whole image. The render loop (render.h) takes the samples; this decides.
//
//   adaptive_sampler a(settings);
//   while (a.plan_round())                        // false once every pixel has enough
//       for each job j, in parallel:              // disjoint pixels: no locks
//           for (const work_item& w : a.job(j))   // samples [w.first, w.first + w.count)
//               a.add(w.pixel, sample, rays);     // in sample order
//   a.write(pixels);                              // the mean of each pixel's samples
//
// Shared by several processes (MPI ranks; settings.ranks > 1): every process holds the whole
// state and plans the same round from it; plan_round() then hands each process the jobs of its
// own part of the round (items cut at equal shares of the round's samples), and after the round
// pack_round() / unpack_round() carry each pixel's new state from the one process that sampled it
// to all the others (the words of pixels sampled elsewhere are zero, so they combine exactly, by
// OR or by sum). Every process then ends the round with exactly the state a lone process would
// have, and the image is the same.
//
// Round 0 takes min_samples samples in every pixel. After each round every pixel gets a target
// count, and a pixel below it takes more, at most doubling its count in one round.
//
// Why these targets. With n_i samples of standard deviation sigma_i in pixel i, the image's
// squared error is sum sigma_i^2 / n_i. For a given cost sum c_i n_i (c_i: rays per sample) it
// is smallest for n_i proportional to sigma_i / sqrt(c_i), Neyman's optimal allocation [1];
// stopping every pixel at the same confidence interval (n_i proportional to sigma_i^2) gives no
// gain at all at equal cost. As a stopping rule: pixel i stops once the 95 % confidence interval
// of its mean, 1.96 sigma_i / sqrt(n_i), is at most
//
//     adaptive_error * value_i * sqrt(n_i / min_samples) * sqrt(c_i / mean c),
//
// "narrow enough relative to the pixel's value", the target loosening as the pixel takes samples
// (the error one more sample removes, sigma_i^2 / n_i^2, per ray, is then the same in every
// pixel: the optimum's condition). value_i is the pixel's luminance after round 0, plus
// value_floor in quadrature, so that dark pixels are not chased to zero.
//
// Why neighbours. sigma_i estimated from a pixel's own few samples is noisy and heavy-tailed
// (glass, caustics: rare bright samples), and a pixel that underestimates it stops early, with a
// large error, and a biased one: the estimate and the mean come from the same samples. So sigma,
// c and the value are averaged over the pixel's 8 neighbours, which mostly share its noise level
// [2], leaving the pixel itself out: 8 times the samples behind each estimate, and a pixel's count
// independent of the samples it averages, so its mean stays unbiased. Every decision is made
// between rounds from the deterministic sums, and sample s of a pixel is always drawn from
// sample_rng(seed, pixel, s), so the image is the same for any thread count.
//
// [1] J. Neyman, "On the two different aspects of the representative method", J. Royal
//     Statistical Society 97(4), 1934, section on optimum allocation; W. G. Cochran, Sampling
//     Techniques, 3rd ed., 1977, section 5.5.
// [2] M. Zwicker et al., "Recent advances in adaptive sampling and reconstruction for Monte
//     Carlo rendering", Computer Graphics Forum 34(2), 2015 (STAR): error estimates filtered
//     over image neighbourhoods.

#include "../core/vec3f.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace rt::detail {

struct adaptive_settings {
    int width = 0, height = 0;
    double error = 0;     // camera::adaptive_error
    int min_samples = 16; // camera::adaptive_min_samples: round 0
    int max_samples = 16; // camera::samples_per_pixel
    int threads = 1;      // jobs are cut so that each thread gets several per round
    int rank = 0, ranks = 1; // this process's part of a round shared by `ranks` processes
};

class adaptive_sampler {
  public:
    struct work_item {
        uint64_t pixel;   // y * width + x
        int first, count; // samples [first, first + count)
    };

    explicit adaptive_sampler(const adaptive_settings& s) : s_(s), pixels_(size_t(s.width) * size_t(s.height)) {
        s_.min_samples = std::min(std::max(2, s_.min_samples), s_.max_samples);
        s_.ranks = std::max(1, s_.ranks);
        s_.rank = std::min(std::max(0, s_.rank), s_.ranks - 1);
    }

    // Plans the next round. False when no pixel needs more samples (on every process alike: they
    // plan from the same state). The jobs are this process's part of the round.
    bool plan_round() {
        items_.clear();
        if (round_ == 0) {
            for (size_t p = 0; p < pixels_.size(); ++p) items_.push_back({uint64_t(p), 0, s_.min_samples});
        } else if (round_ < max_rounds && s_.min_samples < s_.max_samples) {
            plan_from_estimates();
        }
        ++round_;
        take_part();
        cut_jobs();
        return !items_.empty();
    }

    // Words per pixel in pack_round(): the sums and squares of its three channels (as the bits of
    // their doubles), its rays and its sample count.
    static constexpr size_t words_per_pixel = 8;

    // The state of every pixel of the round (in the order of the round's items): the pixels this
    // process sampled, zeros for the others.
    std::vector<uint64_t> pack_round() const {
        std::vector<uint64_t> words(items_.size() * words_per_pixel, 0);
        for (size_t i = part_begin_; i < part_end_; ++i) {
            const pixel_stats& p = pixels_[items_[i].pixel];
            uint64_t* w = &words[i * words_per_pixel];
            for (int k = 0; k < 3; ++k) {
                std::memcpy(&w[k], &p.sum[k], sizeof(double));
                std::memcpy(&w[3 + k], &p.squares[k], sizeof(double));
            }
            w[6] = p.rays;
            w[7] = uint64_t(p.n);
        }
        return words;
    }

    // Takes every pixel's state of the round from `words`: pack_round()'s words of all processes,
    // combined (each pixel's from the process that sampled it).
    void unpack_round(const std::vector<uint64_t>& words) {
        if (words.size() != items_.size() * words_per_pixel) return; // not this round's: nothing to take
        for (size_t i = 0; i < items_.size(); ++i) {
            pixel_stats& p = pixels_[items_[i].pixel];
            const uint64_t* w = &words[i * words_per_pixel];
            for (int k = 0; k < 3; ++k) {
                std::memcpy(&p.sum[k], &w[k], sizeof(double));
                std::memcpy(&p.squares[k], &w[3 + k], sizeof(double));
            }
            p.rays = w[6];
            p.n = int(w[7]);
        }
    }

    size_t job_count() const { return jobs_.empty() ? 0 : jobs_.size() - 1; }
    struct range {
        const work_item *b, *e;
        const work_item* begin() const { return b; }
        const work_item* end() const { return e; }
    };
    range job(size_t j) const { return {items_.data() + jobs_[j], items_.data() + jobs_[j + 1]}; }

    // Records one sample of a pixel, and the rays it took; in sample order, so that the sums (and
    // the image) are the same for any thread count.
    void add(uint64_t pixel, const vec3f& c, uint64_t rays) {
        pixel_stats& p = pixels_[pixel];
        const float v[3] = {c.x, c.y, c.z};
        for (int k = 0; k < 3; ++k) {
            p.sum[k] += v[k];
            p.squares[k] += double(v[k]) * v[k];
        }
        p.rays += rays;
        ++p.n;
    }

    // The mean of each pixel's samples, RGB, row by row. A pixel without samples (only after an
    // interrupted render) is black: 0/0 would be NaN.
    void write(std::vector<float>& rgb) const {
        for (size_t i = 0; i < pixels_.size(); ++i)
            for (int k = 0; k < 3; ++k)
                rgb[i * 3 + size_t(k)] = pixels_[i].n > 0 ? static_cast<float>(pixels_[i].sum[k] / pixels_[i].n) : 0.0f;
    }

    // The samples pixel i has taken so far.
    int samples(size_t i) const { return pixels_[i].n; }
    size_t pixel_count() const { return pixels_.size(); }

  private:
    struct pixel_stats {
        double sum[3] = {0, 0, 0}, squares[3] = {0, 0, 0};
        uint64_t rays = 0;
        int n = 0;
    };

    static constexpr int max_rounds = 64; // a backstop: targets converge in about log2(spp) rounds
    static constexpr double z95 = 1.96;   // the 95 % two-sided normal quantile
    // Neighbours: the 3x3 window. Measured on the cover scene against 5x5: slightly lower error
    // at equal rays, and no bias either way (see docs/accuracy.md).
    static constexpr int radius = 1;
    // The value below which "relative to the pixel's value" gives way to absolute: 0.3 of white.
    // docs/accuracy.md's RMSE wants no floor (equal weight for every pixel), relMSE one of 0.1; 0.3
    // keeps most of the gain on both (Neyman's optimum on the cover: 1.35x and 1.29x the rays).
    static constexpr double value_floor = 0.3;

    // The mean of v over the (2r+1)^2 window around each pixel, clipped at the image's edges,
    // leaving out the pixel itself (unless it is alone).
    std::vector<double> neighbourhood_mean(const std::vector<double>& v, int r) const {
        const int w = s_.width, h = s_.height;
        std::vector<double> rows(v.size()), out(v.size());
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double sum = 0;
                for (int i = std::max(0, x - r); i <= std::min(w - 1, x + r); ++i) sum += v[size_t(y) * w + i];
                rows[size_t(y) * w + x] = sum;
            }
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double sum = 0;
                for (int j = std::max(0, y - r); j <= std::min(h - 1, y + r); ++j) sum += rows[size_t(j) * w + x];
                int count = (std::min(w - 1, x + r) - std::max(0, x - r) + 1) *
                            (std::min(h - 1, y + r) - std::max(0, y - r) + 1);
                size_t i = size_t(y) * w + x;
                out[i] = count > 1 ? (sum - v[i]) / (count - 1) : v[i];
            }
        return out;
    }

    void plan_from_estimates() {
        const size_t count = pixels_.size();
        std::vector<double> variance(count), cost(count);
        for (size_t i = 0; i < count; ++i) {
            const pixel_stats& p = pixels_[i];
            double n = p.n, v = 0;
            // The RMSE averages the three channels' squared errors: so does this variance.
            for (int k = 0; k < 3; ++k) v += std::max(0.0, (p.squares[k] - p.sum[k] * p.sum[k] / n) / (n - 1));
            variance[i] = v / 3;
            cost[i] = double(p.rays) / n;
        }
        if (round_ == 1) {
            // Fixed after round 0, so that the targets do not drift with the running means. The
            // value is Rec. 709 luminance: "relative to its value" as a viewer sees it.
            std::vector<double> luminance(count);
            double total_cost = 0;
            for (size_t i = 0; i < count; ++i) {
                const pixel_stats& p = pixels_[i];
                luminance[i] = (0.2126 * p.sum[0] + 0.7152 * p.sum[1] + 0.0722 * p.sum[2]) / p.n;
                total_cost += cost[i];
            }
            luminance = neighbourhood_mean(luminance, radius);
            value_.resize(count);
            for (size_t i = 0; i < count; ++i)
                value_[i] = std::sqrt(luminance[i] * luminance[i] + value_floor * value_floor);
            mean_cost_ = total_cost / double(count);
        }
        // A pixel's own samples take no part in deciding how many it gets: its count is then
        // independent of the samples it averages, and its mean unbiased (to first order: its
        // samples do shape its neighbours' counts).
        variance = neighbourhood_mean(variance, radius);
        cost = neighbourhood_mean(cost, radius);
        for (size_t i = 0; i < count; ++i) {
            const int n = pixels_[i].n;
            // The count at which the confidence interval meets the target (see the top).
            double relative_cost = mean_cost_ > 0 ? std::max(cost[i] / mean_cost_, 1e-3) : 1;
            double target =
                z95 * std::sqrt(variance[i] * s_.min_samples) / (s_.error * value_[i] * std::sqrt(relative_cost));
            if (!(target > n) || n >= s_.max_samples) continue; // narrow enough, or at the cap
            double deficit = std::ceil(std::min(target, double(s_.max_samples))) - n;
            // At least a quarter more (fewer, larger rounds), at most double (estimates improve).
            int more = int(std::min(std::max(deficit, std::max(1.0, n / 4.0)), double(n)));
            more = std::min(more, s_.max_samples - n);
            items_.push_back({uint64_t(i), n, more});
        }
    }

    // This process's items of the round: a contiguous run of them, cut where the samples before an
    // item reach an equal share of the round's samples (the same cut on every process: the items
    // and the arithmetic are the same). Alone, it takes them all.
    void take_part() {
        part_begin_ = 0;
        part_end_ = items_.size();
        if (s_.ranks == 1) return;
        uint64_t total = 0;
        for (const work_item& w : items_) total += uint64_t(w.count);
        // The process an item goes to: floor(samples before it * ranks / total), in double (the
        // product may exceed 64 bits; the same on every process, and non-decreasing along the items).
        auto owner = [&](uint64_t before) {
            return std::min(s_.ranks - 1, int(std::floor(double(before) / double(total) * double(s_.ranks))));
        };
        uint64_t before = 0;
        bool begun = false;
        part_begin_ = part_end_ = items_.size();
        for (size_t i = 0; i < items_.size(); ++i) {
            const int r = owner(before);
            if (r == s_.rank && !begun) {
                part_begin_ = i;
                begun = true;
            }
            if (r > s_.rank) {
                part_end_ = i;
                break;
            }
            before += uint64_t(items_[i].count);
        }
        if (!begun) part_begin_ = part_end_;
    }

    // Cuts this process's work of the round into jobs of about equal sample counts, many per
    // thread: threads wait for each other at the end of a round, for half a job on average.
    void cut_jobs() {
        jobs_.assign(1, part_begin_);
        uint64_t total = 0;
        for (size_t i = part_begin_; i < part_end_; ++i) total += uint64_t(items_[i].count);
        uint64_t per_job = std::max<uint64_t>(64, total / (uint64_t(std::max(1, s_.threads)) * 64));
        uint64_t in_job = 0;
        for (size_t i = part_begin_; i < part_end_; ++i) {
            in_job += uint64_t(items_[i].count);
            if (in_job >= per_job || i + 1 == part_end_) {
                jobs_.push_back(i + 1);
                in_job = 0;
            }
        }
    }

    adaptive_settings s_;
    std::vector<pixel_stats> pixels_;
    std::vector<double> value_; // value_i of the stopping rule, fixed after round 0
    double mean_cost_ = 1;      // mean rays per sample over the image after round 0
    int round_ = 0;
    std::vector<work_item> items_;
    size_t part_begin_ = 0, part_end_ = 0; // this process's items of the round
    std::vector<size_t> jobs_;
};

} // namespace rt::detail
