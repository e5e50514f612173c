#pragma once
// Baked lighting: every surface side of a solved scene as a tile of texels in one atlas, each
// texel the side's reconstructed radiosity (sampling/solution_reconstruction.h) at its centre.
//
// A side's tile is w x h texels over its (u, v) parameter box, w = ceil(length_u * density),
// h = ceil(length_v * density) (at least 2 each). Its corners get the texture coordinates
// (x0 + u w, y0 + v h) / atlas size (texels, row 0 the image's first row), and a viewer
// interpolates them linearly over each of the side's triangles (a quad's two share the diagonal
// from (0, 0) to (1, 1)); so texel (i, j) holds the radiosity at the point of the side that its
// centre, (a, b) = ((i + 0.5) / w, (j + 0.5) / h), lands on that way: the triangle's corners
// blended by the barycentric coordinates of (a, b). On a parallelogram or a triangle that is the
// point (u, v) = (a, b); on any other quad (a trapezoid, as the Cornell box's floor) the
// bilinear (u, v) of that point, which differs. Around each tile a gutter of kLightmapGutter texels repeats its
// border texels, so filtering at a tile's edge never reads a neighbour. A triangle's texels
// beyond its hypotenuse hold the value at the nearest point of the triangle. Where a method has
// no value (behind barriers, under excluded regions but for a sliver along their outlines on a quad
// that is no parallelogram: SideSampling::outline_band_m) a texel holds 0; `export` warns of those
// outside excluded regions.

#include <functional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/progress.h"
#include "sampling/solution_reconstruction.h"
#include "scene/scene.h"
#include "solver/solution.h"

namespace radrecon {

/// Texels repeated around each tile (for bilinear filtering at its border).
inline constexpr int kLightmapGutter = 2;
/// The largest atlas side, texels (what GPUs take as one texture).
inline constexpr int kMaxLightmapSide = 16384;

/// Where one side lies in the atlas.
struct LightmapTile {
  size_t solution_side = 0;  ///< index into Solution::surfaces
  SideRef side;              ///< the scene side
  int x0 = 0, y0 = 0;        ///< the tile's first texel (its gutter outside it), atlas texels
  int width = 0, height = 0; ///< texels along u and v
};

struct LightmapAtlas {
  Image radiosity_w_m2{1, 1};  ///< linear, W/m^2 per channel; row 0 the first row of the image
  std::vector<LightmapTile> tiles;
  double texels_per_metre = 0;
  /// Texels of the tiles (gutters aside), and those where the method gave no value outside the
  /// sides' excluded regions (outside=none, beyond a radius, cut off by barriers): they hold 0.
  /// Texels in an excluded region (hidden) hold 0 too, and are not counted; but for those within
  /// the side's frame bend of its outline, which hold the value just outside it.
  size_t texels = 0, texels_without_value = 0;

  /// The texture coordinate of the side's parameters (u, v), in [0, 1]^2 of the atlas.
  Vec2 texture_coordinate(const LightmapTile& tile, double u, double v) const;
};

/// An atlas's size, texels.
struct LightmapSize {
  int width = 0, height = 0;
  double texels() const { return static_cast<double>(width) * height; }
};

/// The size of the atlas that bake_lightmaps() would lay out for `texels_along_longest`, found
/// without allocating it; throws as bake_lightmaps() does beyond kMaxLightmapSide.
LightmapSize lightmap_size(const Scene& scene, const Solution& solution, int texels_along_longest, const std::string& where);

/// The most texels along the longest edge, fewer than `texels_along_longest`, whose atlas is
/// within kMaxLightmapSide and passes `fits` (e.g. the memory available); 1 if not even 2 do.
/// Found by halving: an atlas grows with its texels, though in no exact proportion.
int most_lightmap_texels_below(const Scene& scene, const Solution& solution, int texels_along_longest,
                               const std::function<bool(LightmapSize)>& fits);

/// Lays out and fills the atlas with `texels_along_longest` (>= 2) texels along the longest
/// surface edge of the solution, every side at that density. Throws UserError naming `where`
/// when the atlas would exceed kMaxLightmapSide, with the most texels that would fit. `progress`
/// (may be null) hears the share of texels filled.
LightmapAtlas bake_lightmaps(const Scene& scene, const Solution& solution, const SolutionReconstruction& reconstruction,
                             int texels_along_longest, const std::string& where, Progress* progress = nullptr);

}  // namespace radrecon
