// RBF fits derived from a nearby subset's factorisation (fit_rbf_near()) against independent
// answers: the subset's own augmented system built here in plain loops, in raw coordinates, and
// solved by full-pivoting LU; exact at the subset's samples; the dropped samples' values never
// enter (bit for bit); each channel as if alone (bit for bit); a subset on one line refused.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "reconstruct/multiquadric_basis.h"

namespace radrecon {
namespace rbf_near_fit_test {

/// The derived fit and the independent solve agree to this, relative to the values' size (1):
/// both are backward stable, and differ by some eps / rcond (measured at most 4.5e-11, the
/// thin-plate spline out to half a box width past the samples; the multiquadrics 5e-12).
constexpr double kIndependentRelative = 1e-9;

struct Data {
  std::vector<Vec2> points;
  std::vector<double> r_sq, values;
};

/// n random points in [0, 4]^2, radii squared in [0.05, 0.2]^2 (zero for the thin-plate spline),
/// `channels` values in [0, 1) each.
Data random_data(int n, int channels, bool radii, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xy(0, 4), value(0, 1), r(0.05, 0.2);
  Data d;
  for (int i = 0; i < n; ++i) {
    d.points.emplace_back(xy(rng), xy(rng));
    d.r_sq.push_back(radii ? std::pow(r(rng), 2) : 0.0);
    for (int c = 0; c < channels; ++c) d.values.push_back(value(rng));
  }
  return d;
}

/// The interpolant through `subset` at the queries, channel 0: [phi P; P^T 0] [a; c] = [f; 0]
/// with phi(d^2 + r_j^2) in raw coordinates and P = [1 x y] with a polynomial.
std::vector<double> independent(const Data& d, int channels, const RbfKernel& kernel, const std::vector<unsigned>& subset,
                                const std::vector<Vec2>& queries) {
  const auto phi = [&](const Vec2& p, unsigned j) {
    const double v = (p - d.points[j]).squaredNorm() + d.r_sq[j];
    if (kernel.is_thin_plate()) return v > 0 ? 0.5 * v * std::log(v) : 0.0;
    return std::pow(v, kernel.mu);
  };
  const Eigen::Index m = static_cast<Eigen::Index>(subset.size()), t = kernel.poly ? 3 : 0;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m + t, m + t);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m + t);
  for (Eigen::Index i = 0; i < m; ++i) {
    const Vec2& p = d.points[subset[static_cast<size_t>(i)]];
    b(i) = d.values[subset[static_cast<size_t>(i)] * static_cast<size_t>(channels)];
    for (Eigen::Index j = 0; j < m; ++j) A(i, j) = phi(p, subset[static_cast<size_t>(j)]);
    if (t > 0) {
      const double u[3] = {1, p.x(), p.y()};
      for (Eigen::Index k = 0; k < t; ++k) A(i, m + k) = A(m + k, i) = u[k];
    }
  }
  const Eigen::VectorXd x = A.fullPivLu().solve(b);
  std::vector<double> out;
  for (const Vec2& q : queries) {
    double v = t > 0 ? x(m) + x(m + 1) * q.x() + x(m + 2) * q.y() : 0.0;
    for (Eigen::Index j = 0; j < m; ++j) v += x(j) * phi(q, subset[static_cast<size_t>(j)]);
    out.push_back(v);
  }
  return out;
}

std::vector<double> evaluate(const RbfFit& fit, const RbfKernel& kernel, int channels, const std::vector<Vec2>& q) {
  std::vector<double> out(q.size() * static_cast<size_t>(channels));
  Eigen::ArrayXd scratch;
  for (size_t k = 0; k < q.size(); ++k) evaluate_rbf_fit(fit, kernel, channels, q[k], scratch, &out[k * channels]);
  return out;
}

/// A random subset of `count` of the n samples, sorted.
std::vector<unsigned> random_subset(unsigned n, unsigned count, std::mt19937& rng) {
  std::vector<unsigned> all(n);
  std::iota(all.begin(), all.end(), 0u);
  std::shuffle(all.begin(), all.end(), rng);
  all.resize(count);
  std::sort(all.begin(), all.end());
  return all;
}

/// `root` with `drop` of its samples removed and `add` of the others put in, sorted.
std::vector<unsigned> nearby(const std::vector<unsigned>& root, unsigned n, int drop, int add, std::mt19937& rng) {
  std::vector<unsigned> kept = root, others;
  std::shuffle(kept.begin(), kept.end(), rng);
  kept.resize(kept.size() - static_cast<size_t>(drop));
  for (unsigned i = 0; i < n; ++i)
    if (!std::binary_search(root.begin(), root.end(), i)) others.push_back(i);
  std::shuffle(others.begin(), others.end(), rng);
  kept.insert(kept.end(), others.begin(), others.begin() + add);
  std::sort(kept.begin(), kept.end());
  return kept;
}

const std::vector<std::pair<std::string, RbfKernel>>& kernels() {
  static const std::vector<std::pair<std::string, RbfKernel>> k = {
      {"multiquadric", RbfKernel::multiquadric(0.5)},
      {"multiquadric + linear", RbfKernel::multiquadric(0.5, 1)},
      {"inverse multiquadric + linear", RbfKernel::multiquadric(-0.5, 1)},
      {"thin-plate", RbfKernel::thin_plate()}};
  return k;
}

TEST(RbfNearFit, AgreesWithAnIndependentSolveOfTheSubsetAndIsExactAtItsSamples) {
  constexpr unsigned n = 150;
  for (const auto& [name, kernel] : kernels()) {
    const Data d = random_data(n, 1, !kernel.is_thin_plate(), 3);
    std::mt19937 rng(11);
    const std::vector<unsigned> root_subset = random_subset(n, 100, rng);
    const RbfRootFit root = fit_rbf_root(d.points, d.r_sq, d.values, 1, kernel, root_subset);
    std::uniform_real_distribution<double> xy(-0.5, 4.5);
    std::vector<Vec2> queries;
    for (int k = 0; k < 40; ++k) queries.emplace_back(xy(rng), xy(rng));
    for (int drop = 0; drop <= 6; drop += 2)
      for (int add = 0; add <= 6; add += 3) {
        const std::vector<unsigned> subset = nearby(root_subset, n, drop, add, rng);
        const std::optional<RbfFit> near = fit_rbf_near(root, d.points, d.r_sq, d.values, 1, kernel, subset);
        ASSERT_TRUE(near.has_value()) << name << ", " << drop << " dropped, " << add << " added";
        EXPECT_EQ(near->subset, subset);
        const std::vector<double> got = evaluate(*near, kernel, 1, queries);
        const std::vector<double> want = independent(d, 1, kernel, subset, queries);
        for (size_t k = 0; k < queries.size(); ++k)
          ASSERT_NEAR(got[k], want[k], kIndependentRelative) << name << ", " << drop << " dropped, " << add
                                                             << " added, query " << k;
        std::vector<Vec2> at;
        for (unsigned s : subset) at.push_back(d.points[s]);
        const std::vector<double> exact = evaluate(*near, kernel, 1, at);
        for (size_t k = 0; k < subset.size(); ++k)
          ASSERT_NEAR(exact[k], d.values[subset[k]], kIndependentRelative) << name << ", sample " << subset[k];
      }
  }
}

TEST(RbfNearFit, TheDroppedSamplesValuesNeverEnter) {
  constexpr unsigned n = 90;
  for (const auto& [name, kernel] : kernels()) {
    Data d = random_data(n, 1, !kernel.is_thin_plate(), 5);
    std::mt19937 rng(6);
    const std::vector<unsigned> root_subset = random_subset(n, 70, rng);
    const std::vector<unsigned> subset = nearby(root_subset, n, 4, 2, rng);
    const auto& basis = kernel;  // a structured binding cannot be captured before C++20's P1091 (clang 14)
    const auto fit = [&] {
      const RbfRootFit root = fit_rbf_root(d.points, d.r_sq, d.values, 1, basis, root_subset);
      return fit_rbf_near(root, d.points, d.r_sq, d.values, 1, basis, subset).value();
    };
    const RbfFit a = fit();
    for (unsigned s = 0; s < n; ++s)
      if (!std::binary_search(subset.begin(), subset.end(), s)) d.values[s] = -3e5 * (1 + s);
    const RbfFit b = fit();
    EXPECT_EQ(a.alpha_by_channel, b.alpha_by_channel) << name;
    EXPECT_EQ(a.poly, b.poly) << name;
  }
}

TEST(RbfNearFit, EachChannelAsIfAlone) {
  constexpr unsigned n = 80;
  for (const auto& [name, kernel] : kernels()) {
    const Data d = random_data(n, 3, !kernel.is_thin_plate(), 7);
    std::mt19937 rng(8);
    const std::vector<unsigned> root_subset = random_subset(n, 60, rng);
    const std::vector<unsigned> subset = nearby(root_subset, n, 3, 3, rng);
    const RbfRootFit root3 = fit_rbf_root(d.points, d.r_sq, d.values, 3, kernel, root_subset);
    const RbfFit all = fit_rbf_near(root3, d.points, d.r_sq, d.values, 3, kernel, subset).value();
    const size_t m = subset.size();
    for (int c = 0; c < 3; ++c) {
      std::vector<double> one;
      for (unsigned s = 0; s < n; ++s) one.push_back(d.values[s * 3 + static_cast<unsigned>(c)]);
      const RbfRootFit root1 = fit_rbf_root(d.points, d.r_sq, one, 1, kernel, root_subset);
      const RbfFit alone = fit_rbf_near(root1, d.points, d.r_sq, one, 1, kernel, subset).value();
      for (size_t a = 0; a < m; ++a)
        ASSERT_EQ(alone.alpha_by_channel[a], all.alpha_by_channel[c * m + a]) << name << ", channel " << c;
      for (int k = 0; k < all.terms; ++k)
        ASSERT_EQ(alone.poly[static_cast<size_t>(k)], all.poly[static_cast<size_t>(c * all.terms + k)]) << name;
    }
  }
}

TEST(RbfNearFit, ASubsetOnOneLineIsLeftToTheDirectFit) {
  // Samples on the line y = x plus two off it: the root spans the plane, the subset without the
  // two does not, and its linear polynomial has fewer terms.
  Data d;
  for (int i = 0; i < 12; ++i) {
    d.points.emplace_back(0.3 * i, 0.3 * i);
    d.r_sq.push_back(0);
    d.values.push_back(std::sin(i));
  }
  d.points.emplace_back(1.0, 2.5), d.points.emplace_back(2.5, 0.5);
  d.r_sq.insert(d.r_sq.end(), {0, 0}), d.values.insert(d.values.end(), {0.2, 0.9});
  std::vector<unsigned> all(14), line(12);
  std::iota(all.begin(), all.end(), 0u), std::iota(line.begin(), line.end(), 0u);
  const RbfKernel kernel = RbfKernel::thin_plate();
  const RbfRootFit root = fit_rbf_root(d.points, d.r_sq, d.values, 1, kernel, all);
  EXPECT_FALSE(fit_rbf_near(root, d.points, d.r_sq, d.values, 1, kernel, line).has_value());
}

}  // namespace rbf_near_fit_test
}  // namespace radrecon
