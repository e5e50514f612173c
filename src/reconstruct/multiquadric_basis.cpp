#include "reconstruct/multiquadric_basis.h"

#include <string>

#include "core/check.h"
#include "core/parse.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/kdtree.h"

namespace radrecon {

std::vector<double> eck_radii_sq(std::span<const Vec2> points, const KdTree2& tree) {
  RR_CHECK_EQ(tree.size(), points.size(), "the tree must be built over the points");
  RR_CHECK_GE(points.size(), size_t{2}, "Eck's radii need at least 2 points");
  std::vector<double> r_sq(points.size());
  unsigned idx[2];
  double d2[2];
  for (size_t i = 0; i < points.size(); ++i) {
    tree.nearest(points[i], 2, idx, d2);  // the point itself (or a duplicate of it) and the next
    if (d2[1] == 0)
      throw ReconstructionError("two samples at the same point (" + format_number(points[i].x()) + ", " +
                                format_number(points[i].y()) + ")");
    r_sq[i] = d2[1];
  }
  return r_sq;
}

}  // namespace radrecon
