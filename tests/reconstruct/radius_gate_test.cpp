// gdal_grid's radius and min_points for the multiquadric and thin-plate: the method's own value
// where at least min_points samples lie within the radius, NaN elsewhere (brute-force counts).

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "reconstruct/methods.h"

namespace radrecon {
namespace radius_gate_test {

TEST(RadiusGate, TheMethodsValueWhereEnoughSamplesAreWithinTheRadiusElseNone) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(0, 4);
  ScatteredSamples s;
  s.channels = 1;
  for (int i = 0; i < 60; ++i) {
    s.points.emplace_back(u(rng), u(rng));
    s.values.push_back(std::sin(s.points.back().x()) + s.points.back().y());
  }
  std::vector<Vec2> q;
  std::uniform_real_distribution<double> wide(-1, 5);
  for (int i = 0; i < 400; ++i) q.emplace_back(wide(rng), wide(rng));
  for (const Method m : {Method::multiquadric, Method::thin_plate})
    for (const int k : {0, 16}) {
      MethodParams plain;
      (m == Method::multiquadric ? plain.multiquadric_k : plain.thin_plate_k) = k;
      MethodParams gated = plain;
      gated.search_radius_m = 0.5;
      gated.min_points = 3;
      std::vector<double> a(q.size()), b(q.size());
      make_scattered_interpolant(m, s, plain).value()->evaluate(q, a);
      make_scattered_interpolant(m, s, gated).value()->evaluate(q, b);
      int values = 0, none = 0;
      for (size_t i = 0; i < q.size(); ++i) {
        int within = 0;
        for (const Vec2& p : s.points) within += (p - q[i]).norm() <= 0.5;
        if (within >= 3) {
          EXPECT_EQ(b[i], a[i]) << method_name(m) << " k=" << k << ": the method's own value";
          ++values;
        } else {
          EXPECT_TRUE(std::isnan(b[i])) << method_name(m) << " k=" << k << ": " << within << " within the radius";
          ++none;
        }
      }
      EXPECT_GT(values, 50);
      EXPECT_GT(none, 50);
    }
}

}  // namespace radius_gate_test
}  // namespace radrecon
