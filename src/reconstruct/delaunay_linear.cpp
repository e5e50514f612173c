#include "reconstruct/delaunay_linear.h"

namespace radrecon {

DelaunayLinear::DelaunayLinear(const ScatteredSamples& samples, OutsideHull outside)
    : mesh_(samples.points, "linear"), values_(samples.values), channels_(samples.channels), outside_(outside) {}

void DelaunayLinear::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const size_t C = static_cast<size_t>(channels_);
  mesh_.evaluate(points, out, channels_, outside_, [&](const DelaunayMesh::Location& loc, double* o) {
    const std::array<unsigned, 3>& v = mesh_.face(static_cast<size_t>(loc.face));
    const double *v0 = &values_[v[0] * C], *v1 = &values_[v[1] * C], *v2 = &values_[v[2] * C];
    for (size_t c = 0; c < C; ++c) o[c] = loc.b[0] * v0[c] + loc.b[1] * v1[c] + loc.b[2] * v2[c];
  });
}

}  // namespace radrecon
