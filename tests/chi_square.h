#pragma once
// Pearson's chi-square goodness-of-fit test, for the statistical tests (test_statistics.cpp).
//
//   chi2::result r = chi2::test(observed, expected);   // counts per cell, same length
//   CHECK(r.p_value > 0.01);
//
// Cells whose expected count is below 5 are pooled, smallest first, until every pooled cell
// expects at least 5: the usual condition for the chi-square approximation to hold (W. G.
// Cochran, "Some methods for strengthening the common chi-square tests", Biometrics 10, 1954).
// The statistic sum (O - E)^2 / E over the k pooled cells is then approximately chi-square with
// k - 1 degrees of freedom when the expected counts are right (they are computed from the
// analytic density, no parameter is fitted).
//
// The p-value is the chi-square upper tail, Q(k/2, x/2), with Q the regularised upper incomplete
// gamma function, evaluated by its power series for x < a + 1 and by its continued fraction
// (modified Lentz) otherwise: Abramowitz and Stegun, Handbook of Mathematical Functions, 6.5.29
// and 6.5.31; Press et al., Numerical Recipes, 3rd ed., section 6.2. The critical value for a
// significance level is found by bisection on it. The Wilson-Hilferty cube-root approximation
// (E. B. Wilson and M. M. Hilferty, "The distribution of chi-square", PNAS 17, 1931) is provided
// as an independent cross-check of both.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace chi2 {

// Regularised upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a), a > 0, x >= 0.
inline double gamma_q(double a, double x) {
    if (x <= 0) return 1.0;
    const double log_prefix = -x + a * std::log(x) - std::lgamma(a); // log(e^-x x^a / Gamma(a))
    if (x < a + 1) {
        // P(a, x) = e^-x x^a / Gamma(a) * sum_n x^n / (a (a+1) ... (a+n))   (A&S 6.5.29)
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 100000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (std::fabs(term) < std::fabs(sum) * 1e-16) break;
        }
        return 1.0 - std::exp(log_prefix) * sum;
    }
    // Q(a, x) = e^-x x^a / Gamma(a) * 1 / (x + 1 - a - 1 (1 - a) / (x + 3 - a - 2 (2 - a) / ...))
    // (A&S 6.5.31 as an even continued fraction), by the modified Lentz method.
    const double tiny = 1e-300;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int n = 1; n < 100000; ++n) {
        double an = -n * (n - a);
        b += 2;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1 / d;
        double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1) < 1e-16) break;
    }
    return std::exp(log_prefix) * h;
}

// P(X > x) for X chi-square with `dof` degrees of freedom.
inline double upper_tail(double x, double dof) { return gamma_q(dof / 2, x / 2); }

// The x with upper_tail(x, dof) = alpha, by bisection (upper_tail decreases in x).
inline double critical_value(double alpha, double dof) {
    double lo = 0, hi = dof + 10;
    while (upper_tail(hi, dof) > alpha) hi *= 2;
    for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
        double mid = 0.5 * (lo + hi);
        (upper_tail(mid, dof) > alpha ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// Wilson-Hilferty: (X / k)^(1/3) is approximately normal with mean 1 - 2/(9k) and variance
// 2/(9k), so the upper-alpha critical value is k (1 - 2/(9k) + z sqrt(2/(9k)))^3 with z the
// upper-alpha standard normal quantile (z = 2.3263478740408408 for alpha = 0.01).
inline double wilson_hilferty(double z, double dof) {
    double v = 2.0 / (9.0 * dof);
    double c = 1 - v + z * std::sqrt(v);
    return dof * c * c * c;
}

struct result {
    double statistic = 0;  // sum over pooled cells of (O - E)^2 / E
    int dof = 0;           // pooled cells - 1
    double p_value = 1;    // upper_tail(statistic, dof)
    int cells = 0;         // cells after pooling
    double observed_where_impossible = 0; // observations in cells whose expected count is 0
    double total_observed = 0, total_expected = 0;

    double critical(double alpha) const { return critical_value(alpha, dof); }
};

// Pools cells with expected count < min_expected (smallest first) and computes the statistic.
inline result test(const std::vector<double>& observed, const std::vector<double>& expected,
                   double min_expected = 5.0) {
    result r;
    const size_t n = observed.size();
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });

    std::vector<double> obs, exp;
    double pool_o = 0, pool_e = 0;
    for (size_t i : order) {
        r.total_observed += observed[i];
        r.total_expected += expected[i];
        if (expected[i] <= 0) r.observed_where_impossible += observed[i];
        if (expected[i] < min_expected || pool_e > 0) {
            // Small cells go into the pool; the pool is closed once it expects enough.
            pool_o += observed[i];
            pool_e += expected[i];
            if (pool_e >= min_expected) {
                obs.push_back(pool_o);
                exp.push_back(pool_e);
                pool_o = pool_e = 0;
            }
        } else {
            obs.push_back(observed[i]);
            exp.push_back(expected[i]);
        }
    }
    if (pool_o > 0 || pool_e > 0) {
        // A pool left below the threshold joins the largest cell so far (or stands alone).
        if (!exp.empty()) {
            obs.back() += pool_o;
            exp.back() += pool_e;
        } else {
            obs.push_back(pool_o);
            exp.push_back(pool_e);
        }
    }
    r.cells = int(exp.size());
    r.dof = r.cells - 1;
    for (size_t i = 0; i < exp.size(); ++i) {
        if (exp[i] > 0) {
            double d = obs[i] - exp[i];
            r.statistic += d * d / exp[i];
        } else if (obs[i] > 0) {
            r.statistic = std::numeric_limits<double>::infinity();
        }
    }
    r.p_value = r.dof > 0 ? upper_tail(r.statistic, r.dof) : 1.0;
    return r;
}

} // namespace chi2
