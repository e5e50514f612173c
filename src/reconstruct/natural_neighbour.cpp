#include "reconstruct/natural_neighbour.h"

#include "core/parallel.h"
#include "reconstruct/natural_neighbour_impl.h"

namespace radrecon {

NaturalNeighbour::NaturalNeighbour(const ScatteredSamples& samples, OutsideHull outside, Barriers barriers,
                                   NeighbourRule rule)
    : impl_(std::make_unique<Impl>()) {
  impl_->barriers = std::move(barriers);
  impl_->rule = rule;
  const std::string name = rule == NeighbourRule::sibson ? "natural-neighbour" : rule == NeighbourRule::laplace ? "laplace" : "sibson-c1";
  const size_t n = samples.points.size();
  if (n < 3) throw ReconstructionError(name + " interpolation needs at least 3 samples, got " + std::to_string(n));
  impl_->values = samples.values;
  impl_->channels = samples.channels;
  impl_->outside = outside;
  impl_->points = samples.points;
  std::vector<std::pair<Point, unsigned>> input;
  input.reserve(n);
  for (size_t i = 0; i < n; ++i) input.emplace_back(Point(samples.points[i].x(), samples.points[i].y()), static_cast<unsigned>(i));
  impl_->dt.insert(input.begin(), input.end());
  if (impl_->dt.number_of_vertices() != n)
    throw ReconstructionError(std::to_string(n - impl_->dt.number_of_vertices()) +
                                   " duplicate sample point(s); " + name + " needs distinct points");
  if (impl_->dt.dimension() < 2) throw ReconstructionError("all samples lie on one line; " + name + " needs a 2-D spread");
  impl_->vertex_of.resize(n);
  for (auto v = impl_->dt.finite_vertices_begin(); v != impl_->dt.finite_vertices_end(); ++v) impl_->vertex_of[v->info()] = v;
  if (!impl_->barriers.empty() && n <= kMaxWholeVisibleSamples &&
      n * impl_->barriers.segments().size() <= kMaxWholeVisiblePairs)
    impl_->visibility = std::make_unique<PointVisibility>(impl_->points, impl_->barriers);
  // Hull edges: the finite edges of the infinite faces, each with the height over it of the
  // finite triangle on it, and split at the samples on it up to rounding (hull_chain.h).
  const HullChains<Delaunay> chains(impl_->dt, impl_->points);
  for (const auto& e : chains.pieces) impl_->hull_pieces.emplace_back(e.a, e.b);
  {
    std::vector<std::pair<unsigned, unsigned>> keys;
    for (const auto& [a, b] : impl_->hull_pieces) keys.push_back(std::minmax(a, b));
    impl_->nearest_piece = std::make_unique<NearestSegment>(impl_->points, impl_->hull_pieces, std::move(keys));
  }
  auto inf = impl_->dt.infinite_vertex();
  auto fc = impl_->dt.incident_faces(inf), done = fc;
  do {
    const int i = fc->index(inf);
    const unsigned a = fc->vertex(Delaunay::ccw(i))->info(), b = fc->vertex(Delaunay::cw(i))->info();
    const Vec2 pa = impl_->points[a], pb = impl_->points[b];
    const Vec2 c = impl_->points[fc->neighbor(i)->vertex(impl_->dt.mirror_index(fc, i))->info()];
    impl_->hull_edges.emplace_back(a, b);
    impl_->hull_edge_height_m.push_back(std::abs(cross(pb - pa, c - pa)) / (pb - pa).norm());
    const auto& range = chains.range(fc, i);
    impl_->hull_edge_pieces.emplace_back(range.begin, range.end);
    impl_->hull_edge_depth_m.push_back(range.depth_m);
  } while (++fc != done);
  // By sample: the hull edges it ends, two; or, no vertex of CGAL's hull, the one it splits, so
  // that a query in a face at it finds the edge. (A thin set's hull vertex may lie within
  // rounding of the hull edge across it too: it keeps its own two.)
  impl_->hull_edges_at.assign(n, {-1, -1});
  for (size_t e = 0; e < impl_->hull_edges.size(); ++e)
    for (const unsigned end : {impl_->hull_edges[e].first, impl_->hull_edges[e].second}) {
      std::array<int, 2>& at = impl_->hull_edges_at[end];
      RR_CHECK(at[1] < 0, "a sample at more than two hull edges");
      (at[0] < 0 ? at[0] : at[1]) = static_cast<int>(e);
    }
  for (size_t e = 0; e < impl_->hull_edges.size(); ++e) {
    const auto [begin, end] = impl_->hull_edge_pieces[e];
    for (size_t k = begin + 1; k < end; ++k) {
      std::array<int, 2>& at = impl_->hull_edges_at[impl_->hull_pieces[k].first];
      if (at[0] < 0) at[0] = static_cast<int>(e);
    }
  }
  if (rule == NeighbourRule::sibson_c1) {
    impl_->gradients = nn::fit_gradients(impl_->dt, impl_->vertex_of, impl_->points, impl_->values, impl_->channels,
                                         impl_->barriers);
    // A slope the samples carry (a border sample's plane: samples.h) is taken as it is.
    RR_CHECK(samples.slopes.empty() || samples.slopes.size() == impl_->gradients.size(),
             "sample slopes do not match the values");
    for (size_t k = 0; k < samples.slopes.size(); ++k)
      if (std::isfinite(samples.slopes[k])) impl_->gradients[k] = samples.slopes[k];
  }
}

NaturalNeighbour::~NaturalNeighbour() = default;

int NaturalNeighbour::channels() const { return impl_->channels; }

const std::vector<std::pair<unsigned, unsigned>>& NaturalNeighbour::hull_edges() const { return impl_->hull_pieces; }

std::vector<std::pair<unsigned, double>> NaturalNeighbour::coordinates(const Vec2& q) const {
  Impl::Scratch scratch;
  Delaunay::Face_handle hint;
  if (impl_->query(q, hint, scratch) != Impl::Kind::coordinates) return {};
  return std::move(scratch.coords);
}

namespace {

/// Runs body(q, kind, scratch) for every query q, kind and scratch.coords as Impl::query() leaves
/// them (kind nothing for a non-finite point), in fixed chunks: each chunk's walk starts at a face
/// of the sample nearest to its first query, then from the face found last (raster queries are
/// coherent). A query on a Delaunay edge may be located in either face, and the coordinates' last
/// bits depend on which; fixed chunks with deterministic starts make that independent of the
/// number of threads. Runs of 4 chunks are handed out to the threads, in parallel from 2 runs on:
/// a chunk costs some 10 us, far more than handing it out. Without `tree_hints` a chunk's walk
/// starts where CGAL starts it (O(sqrt n) steps, but no k-d tree to build: for the few points a
/// raster served face by face leaves).
template <typename Impl, typename Body>
void for_each_query(const Impl& impl, std::span<const Vec2> points, Body&& body, bool tree_hints = true) {
  constexpr std::int64_t kChunk = 64, kChunksPerRun = 4;
  const std::int64_t n = static_cast<std::int64_t>(points.size());
  using Scratch = typename Impl::Scratch;
  parallel_for_with_scratch<Scratch>(0, (n + kChunk - 1) / kChunk, kChunksPerRun, 2 * kChunksPerRun, [&](std::int64_t chunk, Scratch& scratch) {
    // A chunk's conflict zones are its own: its walks start from its own first query, whatever
    // the thread ran before (which face an edge's point is located in decides the hull-edge test).
    scratch.zone.forget();
    Delaunay::Face_handle hint;
    const size_t first = static_cast<size_t>(chunk * kChunk);
    if (tree_hints && points[first].allFinite()) {
      unsigned nearest[1];
      double nearest_d2[1];
      impl.tree().nearest(points[first], 1, nearest, nearest_d2);
      hint = impl.vertex_of[nearest[0]]->face();
    }
    for (std::int64_t k = chunk * kChunk; k < std::min(n, (chunk + 1) * kChunk); ++k) {
      const size_t q = static_cast<size_t>(k);
      const typename Impl::Kind kind = points[q].allFinite() ? impl.query(points[q], hint, scratch) : Impl::Kind::nothing;
      body(q, kind, scratch);
    }
  });
}

/// The interpolant's values at the points (NaturalNeighbour::evaluate()).
template <typename Impl>
void evaluate_points(const Impl& impl, std::span<const Vec2> points, std::span<double> out, bool tree_hints) {
  const int C = impl.channels;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  for_each_query(impl, points, [&](size_t q, typename Impl::Kind kind, const typename Impl::Scratch& scratch) {
    double* o = &out[q * C];
    if (kind == Impl::Kind::coordinates || (kind == Impl::Kind::on_hull && impl.outside == OutsideHull::nearest)) {
      impl.combine(scratch.coords, o);
    } else {
      for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
    }
  }, tree_hints);
}

}  // namespace

void NaturalNeighbour::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  evaluate_points(*impl_, points, out, true);
}

/// The face-by-face raster (SibsonRaster) pays for its faces (some 180 bytes each, twice as many
/// as the samples) with its points: a raster of fewer points than this many a face goes query by
/// query (1,000,000 samples onto 500 x 500 took 3.65 s and 781 MiB face by face, 2.80 s and 263
/// MiB query by query; docs/benchmarks.md).
constexpr double kFaceRasterLeastPointsPerFace = 1;

void NaturalNeighbour::evaluate_raster(const Raster& raster, size_t first, size_t count, std::span<double> out) const {
  const double point_count = static_cast<double>(raster.width) * static_cast<double>(raster.height);
  if (impl_->rule != NeighbourRule::sibson || !impl_->barriers.empty() ||
      point_count < kFaceRasterLeastPointsPerFace * static_cast<double>(impl_->dt.number_of_faces()))
    return Interpolant::evaluate_raster(raster, first, count, out);
  const SibsonRaster& faces = impl_->raster.get([&] {
    return std::make_unique<SibsonRaster>(impl_->dt, impl_->points, impl_->values, impl_->channels, impl_->hull_pieces);
  });
  if (!faces.usable()) return Interpolant::evaluate_raster(raster, first, count, out);
  std::vector<size_t> unserved;
  faces.evaluate(raster, first, count, out, unserved);
  if (unserved.empty()) return;
  const size_t C = static_cast<size_t>(impl_->channels), width = static_cast<size_t>(raster.width);
  std::vector<Vec2> points;
  points.reserve(unserved.size());
  for (const size_t k : unserved) points.push_back(raster.point((first + k) % width, (first + k) / width));
  std::vector<double> values(points.size() * C);
  // Few points (those by the hull or on samples) walk from CGAL's start rather than have a k-d
  // tree built for them; many (a raster reaching far past the hull) are worth one.
  constexpr size_t kLeastForTreeHints = 4096;
  evaluate_points(*impl_, points, values, points.size() >= kLeastForTreeHints);
  for (size_t u = 0; u < unserved.size(); ++u)
    std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(u * C), C, out.begin() + static_cast<std::ptrdiff_t>(unserved[u] * C));
}

void NaturalNeighbour::visit_coordinates(
    std::span<const Vec2> points,
    const std::function<void(size_t, std::span<const std::pair<unsigned, double>>)>& visit) const {
  for_each_query(*impl_, points, [&](size_t q, Impl::Kind kind, const Impl::Scratch& scratch) {
    if (kind == Impl::Kind::coordinates) visit(q, scratch.coords);
    else visit(q, {});
  });
}

}  // namespace radrecon
