// Area-to-area form factors near the shooter: the visible point form factor integrated over the
// receiving quad by adaptive Gauss-Legendre cubature (area_visible_form_factor(), visibility.h).

#include <array>
#include <cmath>
#include <vector>

#include "solver/visibility.h"

namespace radrecon {

namespace {

/// The receiver as the bilinear patch x(s, t) = sum of its corners' weights, (s, t) in [0,1]^2.
struct BilinearQuad {
  std::array<Vec3, 4> c;
  Vec3 point(double s, double t) const {
    return (1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + s * t * c[2] + (1 - s) * t * c[3];
  }
  /// |dx/ds x dx/dt|, m^2 per unit of (s, t) area.
  double jacobian(double s, double t) const {
    const Vec3 xs = (1 - t) * (c[1] - c[0]) + t * (c[2] - c[3]);
    const Vec3 xt = (1 - s) * (c[3] - c[0]) + s * (c[2] - c[1]);
    return xs.cross(xt).norm();
  }
};

class Cubature {
 public:
  Cubature(const BilinearQuad& patch, const Vec3& n, const ConvexPolygon& shooter, const Vec3& shooter_normal,
           const std::vector<const Occluder*>& occluders)
      : patch_(patch), n_(n), shooter_(shooter), shooter_normal_(shooter_normal), occluders_(occluders) {}

  /// Integral of F(x -> S) over the square [s0, s1] x [t0, t1] of (s, t), m^2: the 2 x 2
  /// Gauss-Legendre rule (exact for bicubics).
  double gauss(double s0, double t0, double s1, double t1) const {
    static const double kNode = 0.5 / std::sqrt(3.0);  // Gauss points at the middle +- this
    const double ds = s1 - s0, dt = t1 - t0, sm = 0.5 * (s0 + s1), tm = 0.5 * (t0 + t1);
    double sum = 0;
    for (double a : {-kNode, kNode})
      for (double b : {-kNode, kNode}) {
        const double s = sm + a * ds, t = tm + b * dt;
        sum += visible_form_factor(patch_.point(s, t), n_, shooter_, shooter_normal_, occluders_) *
               patch_.jacobian(s, t);
      }
    return 0.25 * ds * dt * sum;
  }

  /// The integral over the square, whose own estimate is `whole`, refined until the quarters
  /// agree with it to `tolerance_m2`.
  double refine(double s0, double t0, double s1, double t1, double whole, int depth, double tolerance_m2) const {
    const double sm = 0.5 * (s0 + s1), tm = 0.5 * (t0 + t1);
    const std::array<std::array<double, 4>, 4> quarters = {
        {{s0, t0, sm, tm}, {sm, t0, s1, tm}, {s0, tm, sm, t1}, {sm, tm, s1, t1}}};
    std::array<double, 4> part;
    double sum = 0;
    for (int k = 0; k < 4; ++k) {
      part[k] = gauss(quarters[k][0], quarters[k][1], quarters[k][2], quarters[k][3]);
      sum += part[k];
    }
    if (depth + 1 >= kMaxAreaFormFactorDepth || std::abs(sum - whole) <= tolerance_m2) return sum;
    double refined = 0;
    for (int k = 0; k < 4; ++k)
      refined += refine(quarters[k][0], quarters[k][1], quarters[k][2], quarters[k][3], part[k], depth + 1,
                        tolerance_m2);
    return refined;
  }

 private:
  const BilinearQuad& patch_;
  const Vec3& n_;
  const ConvexPolygon& shooter_;
  const Vec3& shooter_normal_;
  const std::vector<const Occluder*>& occluders_;
};

}  // namespace

double area_visible_form_factor(const std::array<Vec3, 4>& receiver, const Vec3& receiver_normal,
                                const ConvexPolygon& shooter, const Vec3& shooter_normal,
                                const std::vector<const Occluder*>& occluders, double tolerance) {
  const BilinearQuad patch{receiver};
  const double area = 0.5 * (receiver[2] - receiver[0]).cross(receiver[3] - receiver[1]).norm();
  if (!(area > 0) || shooter.empty()) return 0.0;
  const Cubature cubature(patch, receiver_normal, shooter, shooter_normal, occluders);
  const double whole = cubature.gauss(0, 0, 1, 1);
  return cubature.refine(0, 0, 1, 1, whole, 0, tolerance * area) / area;
}

}  // namespace radrecon
