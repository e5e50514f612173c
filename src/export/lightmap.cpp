#include "export/lightmap.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#include "core/error.h"
#include "reconstruct/interpolant.h"
#include "scene/side.h"

namespace radrecon {

namespace {

/// The parameters of the surface point that a texel centre (a, b) of its tile lands on when a
/// viewer interpolates the corners' texture coordinates over the side's triangles (header).
Vec2 texel_point(const Surface& surface, double a, double b) {
  if (surface.is_triangle()) {
    if (a + b <= 1) return {a, b};
    // Beyond the hypotenuse: the nearest point of the triangle.
    const double excess = 0.5 * (a + b - 1);
    const double u = std::clamp(a - excess, 0.0, 1.0);
    return {u, std::clamp(b - excess, 0.0, 1.0 - u)};
  }
  const auto& c = surface.corners;  // (u, v) = (0,0), (1,0), (1,1), (0,1)
  const Vec3 p = a >= b ? Vec3((1 - a) * c[0] + (a - b) * c[1] + b * c[2])
                        : Vec3((1 - b) * c[0] + a * c[2] + (b - a) * c[3]);
  const std::optional<Vec2> uv = surface.parameters(p);
  return uv ? *uv : Vec2(a, b);  // a point of the quad's plane inside it: always found
}

/// The tiles of an atlas of `texels` along the scene's longest edge (`longest_m`) and its size;
/// whether it fits in the largest texture (fits()), else the first side too large alone.
struct Packing {
  std::vector<LightmapTile> tiles;
  int width = 0, height = 0;
  std::string too_large_side, too_large_size;  ///< a side that alone exceeds it: its name, "W x H"
  bool fits() const { return too_large_side.empty() && width <= kMaxLightmapSide && height <= kMaxLightmapSide; }
};

Packing pack(const Scene& scene, const Solution& solution, int texels_along_longest, double longest_m) {
  Packing out;
  constexpr int g = kLightmapGutter;
  // Tile sizes, then shelves: tallest first (ties in the solution's order), rows of the width
  // that makes the atlas about square.
  double area = 0;
  int widest = 0;
  for (size_t k = 0; k < solution.surfaces.size(); ++k) {
    const SurfaceSolution& s = solution.surfaces[k];
    const std::optional<SideRef> side = find_side(scene, s.name);
    RR_CHECK(side.has_value(), "a solution side missing from its scene");
    LightmapTile t;
    t.solution_side = k;
    t.side = *side;
    // The length's share of the longest first: x / x is exactly 1, so the longest side gets
    // exactly the texels asked for (length * density rounded up to one more at some lengths).
    const double w = std::ceil(texels_along_longest * (s.length_u_m / longest_m)),
                 h = std::ceil(texels_along_longest * (s.length_v_m / longest_m));
    if (!(w + 2 * g <= kMaxLightmapSide && h + 2 * g <= kMaxLightmapSide)) {
      out.too_large_side = s.name;
      out.too_large_size = std::to_string(static_cast<long long>(w)) + " x " + std::to_string(static_cast<long long>(h));
      return out;
    }
    t.width = std::max(2, static_cast<int>(w));
    t.height = std::max(2, static_cast<int>(h));
    area += static_cast<double>(t.width + 2 * g) * (t.height + 2 * g);
    widest = std::max(widest, t.width + 2 * g);
    out.tiles.push_back(t);
  }
  std::vector<size_t> order(out.tiles.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return out.tiles[a].height > out.tiles[b].height; });
  const int row_width = std::max(widest, static_cast<int>(std::ceil(std::sqrt(area))));
  int x = 0, y = 0, shelf = 0;
  for (const size_t k : order) {
    LightmapTile& t = out.tiles[k];
    if (x + t.width + 2 * g > row_width) x = 0, y += shelf, shelf = 0;
    t.x0 = x + g;
    t.y0 = y + g;
    x += t.width + 2 * g;
    shelf = std::max(shelf, t.height + 2 * g);
    out.width = std::max(out.width, x);
  }
  out.height = y + shelf;
  return out;
}

}  // namespace

Vec2 LightmapAtlas::texture_coordinate(const LightmapTile& tile, double u, double v) const {
  return {(tile.x0 + u * tile.width) / radiosity_w_m2.width(), (tile.y0 + v * tile.height) / radiosity_w_m2.height()};
}

namespace {

/// The longest surface edge of the solution, metres: --texels texels along it.
double longest_edge_m(const Solution& solution) {
  double longest_m = 0;
  for (const SurfaceSolution& s : solution.surfaces)
    longest_m = std::max(longest_m, mesh_extent_m(s.frame(), s.triangle));
  RR_CHECK(longest_m > 0, "a solution of no extent");
  return longest_m;
}

/// pack(), or UserError naming `where` when the atlas exceeds the largest texture, with the most
/// texels that would fit.
Packing checked_packing(const Scene& scene, const Solution& solution, int texels_along_longest, const std::string& where) {
  RR_CHECK(texels_along_longest >= 2, "a lightmap needs 2 texels along the longest edge");
  Packing packing = pack(scene, solution, texels_along_longest, longest_edge_m(solution));
  if (packing.fits()) return packing;
  const int lo = most_lightmap_texels_below(scene, solution, texels_along_longest, [](LightmapSize) { return true; });
  const std::string most = lo >= 2 ? "; at most " + std::to_string(lo) + " fit" : "";
  if (!packing.too_large_side.empty())
    throw UserError(where, "side '" + packing.too_large_side + "' would need " + packing.too_large_size +
                               " texels and a gutter of " + std::to_string(kLightmapGutter) +
                               " around them, more than the largest texture (" + std::to_string(kMaxLightmapSide) +
                               " texels a side)" + most);
  throw UserError(where, "the atlas would be " + std::to_string(packing.width) + " x " + std::to_string(packing.height) +
                             " texels, more than the largest texture (" + std::to_string(kMaxLightmapSide) + " a side)" +
                             most);
}

}  // namespace

int most_lightmap_texels_below(const Scene& scene, const Solution& solution, int texels_along_longest,
                               const std::function<bool(LightmapSize)>& fits) {
  const double longest_m = longest_edge_m(solution);
  int lo = 1, hi = texels_along_longest;  // lo fits (or is 1: none does), hi does not
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    const Packing p = pack(scene, solution, mid, longest_m);
    (p.fits() && fits({p.width, p.height}) ? lo : hi) = mid;
  }
  return lo;
}

LightmapSize lightmap_size(const Scene& scene, const Solution& solution, int texels_along_longest, const std::string& where) {
  const Packing packing = checked_packing(scene, solution, texels_along_longest, where);
  return {packing.width, packing.height};
}

LightmapAtlas bake_lightmaps(const Scene& scene, const Solution& solution, const SolutionReconstruction& reconstruction,
                             int texels_along_longest, const std::string& where, Progress* progress) {
  Packing packing = checked_packing(scene, solution, texels_along_longest, where);
  LightmapAtlas atlas;
  atlas.texels_per_metre = texels_along_longest / longest_edge_m(solution);
  atlas.tiles = std::move(packing.tiles);
  const int atlas_width = packing.width, atlas_height = packing.height;
  atlas.radiosity_w_m2 = Image(atlas_width, atlas_height);
  Image& img = atlas.radiosity_w_m2;
  for (int j = 0; j < atlas_height; ++j)
    for (int i = 0; i < atlas_width; ++i) img.at(i, j) = Rgb::Zero();

  // Each tile in batches of rows (at most kEvaluateBatch texels, or one row), then its gutter: a
  // gutter texel repeats the nearest texel of the tile.
  std::vector<Vec2> points;
  std::vector<double> values;
  double texels = 0, filled = 0;
  for (const LightmapTile& t : atlas.tiles) texels += static_cast<double>(t.width) * t.height;
  for (const LightmapTile& t : atlas.tiles) {
    const SurfaceSolution& s = solution.surfaces[t.solution_side];
    const Surface& surface = scene.surfaces[t.side.surface];
    const Interpolant* f = reconstruction.side(t.side);
    RR_CHECK(f != nullptr, "a side without its reconstruction");
    const SurfaceFrame frame = s.frame();
    const int channels = f->channels();
    const int rows_per_batch = std::max(1, static_cast<int>(kEvaluateBatch / static_cast<size_t>(t.width)));
    for (int j0 = 0; j0 < t.height; j0 += rows_per_batch) {
      const int j1 = std::min(t.height, j0 + rows_per_batch);
      points.clear();
      for (int j = j0; j < j1; ++j)
        for (int i = 0; i < t.width; ++i)
          points.push_back(frame.st(texel_point(surface, (i + 0.5) / t.width, (j + 0.5) / t.height)));
      values.assign(points.size() * static_cast<size_t>(channels), 0.0);
      f->evaluate(points, values);
      filled += static_cast<double>(points.size());
      atlas.texels += points.size();
      if (progress != nullptr) progress->update(filled / texels, "the lightmap's texels filled");
      for (int j = j0; j < j1; ++j)
        for (int i = 0; i < t.width; ++i) {
          const size_t k = static_cast<size_t>(j - j0) * t.width + i;
          Rgb& c = img.at(t.x0 + i, t.y0 + j);
          bool without_value = false;
          for (int ch = 0; ch < 3; ++ch) {
            const double v = values[k * channels + std::min(ch, channels - 1)];
            c[ch] = std::isfinite(v) ? v : 0.0;
            without_value = without_value || !std::isfinite(v);
          }
          if (without_value && !in_excluded_region(s.excluded, points[k])) ++atlas.texels_without_value;
        }
    }
    constexpr int g = kLightmapGutter;
    for (int j = -g; j < t.height + g; ++j)
      for (int i = -g; i < t.width + g; ++i)
        if (i < 0 || j < 0 || i >= t.width || j >= t.height)
          img.at(t.x0 + i, t.y0 + j) = img.at(t.x0 + std::clamp(i, 0, t.width - 1), t.y0 + std::clamp(j, 0, t.height - 1));
  }
  return atlas;
}

}  // namespace radrecon
