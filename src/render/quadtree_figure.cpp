#include "render/quadtree_figure.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "render/ground_map.h"

namespace radrecon {

Image quadtree_figure(const CellSamples& cells, double x0, double y0, double extent_m, double white_w_m2,
                      const QuadtreeFigureStyle& style) {
  RR_CHECK(extent_m > 0 && style.size_px > 0, "figure size must be positive");
  const int S = style.size_px;
  Image img(S, S);
  auto to_px = [&](double x) { return (x - x0) / extent_m * S; };
  for (size_t k = 0; k < cells.cells.size(); ++k) {
    const Rect& r = cells.cells[k];
    const int i0 = std::clamp(static_cast<int>(std::lround(to_px(r.x0))), 0, S);
    const int i1 = std::clamp(static_cast<int>(std::lround(to_px(r.x1))), 0, S);
    const int j0 = std::clamp(static_cast<int>(std::lround((r.y0 - y0) / extent_m * S)), 0, S);
    const int j1 = std::clamp(static_cast<int>(std::lround((r.y1 - y0) / extent_m * S)), 0, S);
    Rgb display;  // sRGB-encoded here, so that the overlay colours keep their values
    for (int c = 0; c < 3; ++c)
      display[c] = srgb_encode(tone_map(cells.values[k * static_cast<size_t>(cells.channels) + static_cast<size_t>(std::min(c, cells.channels - 1))], white_w_m2));
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) {
        const bool border = i == i0 || j == j0 || i == i1 - 1 || j == j1 - 1;
        img.at(i, S - 1 - j) = border ? style.edge : display;
      }
  }
  for (const Rect& r : cells.cells) {
    const Vec2 c = r.center();
    const int ci = static_cast<int>(to_px(c.x())), cj = static_cast<int>((c.y() - y0) / extent_m * S);
    for (int dj = -style.point_radius_px; dj <= style.point_radius_px; ++dj)
      for (int di = -style.point_radius_px; di <= style.point_radius_px; ++di) {
        const int i = ci + di, j = cj + dj;
        if (i >= 0 && i < S && j >= 0 && j < S && di * di + dj * dj <= style.point_radius_px * style.point_radius_px)
          img.at(i, S - 1 - j) = style.point;
      }
  }
  return img;
}

}  // namespace radrecon
