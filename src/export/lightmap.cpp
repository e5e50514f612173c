#include "export/lightmap.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "reconstruct/interpolant.h"
#include "scene/side.h"

namespace radrecon {

namespace {

/// The parameters of a texel centre, moved onto a triangle's domain when beyond its hypotenuse.
Vec2 onto_domain(double u, double v, bool triangle) {
  if (!triangle || u + v <= 1) return {u, v};
  const double excess = 0.5 * (u + v - 1);
  u = std::clamp(u - excess, 0.0, 1.0);
  v = std::clamp(v - excess, 0.0, 1.0);
  return {u, 1 - u < v ? 1 - u : v};
}

}  // namespace

Vec2 LightmapAtlas::texture_coordinate(const LightmapTile& tile, double u, double v) const {
  return {(tile.x0 + u * tile.width) / radiosity_w_m2.width(), (tile.y0 + v * tile.height) / radiosity_w_m2.height()};
}

LightmapAtlas bake_lightmaps(const Scene& scene, const Solution& solution, const SolutionReconstruction& reconstruction,
                             double texels_per_metre, const std::string& where) {
  RR_CHECK(texels_per_metre > 0, "lightmap density must be positive");
  LightmapAtlas atlas;
  atlas.texels_per_metre = texels_per_metre;
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
    const double w = std::ceil(s.length_u_m * texels_per_metre), h = std::ceil(s.length_v_m * texels_per_metre);
    if (!(w + 2 * g <= kMaxLightmapSide && h + 2 * g <= kMaxLightmapSide))
      throw UserError(where, "side '" + s.name + "' would need " + std::to_string(w) + " x " + std::to_string(h) +
                                 " texels, more than the largest texture (" + std::to_string(kMaxLightmapSide) +
                                 " texels a side); lower the density");
    t.width = std::max(2, static_cast<int>(w));
    t.height = std::max(2, static_cast<int>(h));
    area += static_cast<double>(t.width + 2 * g) * (t.height + 2 * g);
    widest = std::max(widest, t.width + 2 * g);
    atlas.tiles.push_back(t);
  }
  std::vector<size_t> order(atlas.tiles.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return atlas.tiles[a].height > atlas.tiles[b].height; });
  const int row_width = std::max(widest, static_cast<int>(std::ceil(std::sqrt(area))));
  int x = 0, y = 0, shelf = 0, atlas_width = 0;
  for (const size_t k : order) {
    LightmapTile& t = atlas.tiles[k];
    if (x + t.width + 2 * g > row_width) x = 0, y += shelf, shelf = 0;
    t.x0 = x + g;
    t.y0 = y + g;
    x += t.width + 2 * g;
    shelf = std::max(shelf, t.height + 2 * g);
    atlas_width = std::max(atlas_width, x);
  }
  const int atlas_height = y + shelf;
  if (atlas_width > kMaxLightmapSide || atlas_height > kMaxLightmapSide) {
    const double fits = texels_per_metre * kMaxLightmapSide / std::max(atlas_width, atlas_height);
    throw UserError(where, "the atlas would be " + std::to_string(atlas_width) + " x " + std::to_string(atlas_height) +
                               " texels, more than the largest texture (" + std::to_string(kMaxLightmapSide) +
                               " a side); at most about " + std::to_string(fits) + " texels per metre fit");
  }
  atlas.radiosity_w_m2 = Image(atlas_width, atlas_height);
  Image& img = atlas.radiosity_w_m2;
  for (int j = 0; j < atlas_height; ++j)
    for (int i = 0; i < atlas_width; ++i) img.at(i, j) = Rgb::Zero();

  std::vector<Vec2> points;
  std::vector<double> values;
  for (const LightmapTile& t : atlas.tiles) {
    const SurfaceSolution& s = solution.surfaces[t.solution_side];
    const Interpolant* f = reconstruction.side(t.side);
    RR_CHECK(f != nullptr, "a side without its reconstruction");
    const SurfaceFrame frame = s.frame();
    points.clear();
    for (int j = 0; j < t.height; ++j)
      for (int i = 0; i < t.width; ++i)
        points.push_back(frame.st(onto_domain((i + 0.5) / t.width, (j + 0.5) / t.height, s.triangle)));
    const int channels = f->channels();
    values.assign(points.size() * static_cast<size_t>(channels), 0.0);
    f->evaluate(points, values);
    // The tile and its gutter: a gutter texel repeats the nearest texel of the tile.
    for (int j = -g; j < t.height + g; ++j)
      for (int i = -g; i < t.width + g; ++i) {
        const size_t k = static_cast<size_t>(std::clamp(j, 0, t.height - 1)) * t.width + std::clamp(i, 0, t.width - 1);
        Rgb c;
        for (int ch = 0; ch < 3; ++ch) {
          const double v = values[k * channels + std::min(ch, channels - 1)];
          c[ch] = std::isfinite(v) ? v : 0.0;
        }
        img.at(t.x0 + i, t.y0 + j) = c;
      }
  }
  return atlas;
}

}  // namespace radrecon
