#pragma once
// The paper's Fig. 1: an adaptive subdivision of a patch, its cells outlined and their centres
// (the sample points of the scattered-data methods) marked, over the radiosity.

#include <span>

#include "core/image.h"
#include "reconstruct/samples.h"

namespace radrecon {

struct QuadtreeFigureStyle {
  int size_px = 800;                      ///< the image is size_px x size_px
  Rgb edge = Rgb(0.85, 0.15, 0.1);        ///< cell outlines (display values)
  Rgb point = Rgb(0.1, 0.35, 1.0);        ///< sample points (display values)
  int point_radius_px = 2;
};

/// Draws `cells` (rectangles in metres, channel 0..2 values in W/m^2) over the square
/// [x0, x0 + extent] x [y0, y0 + extent], radiosity tone-mapped as radiosity_map() does with
/// `white_w_m2`, y up. Written as display values (encode with sRGB for the radiosity only).
Image quadtree_figure(const CellSamples& cells, double x0, double y0, double extent_m, double white_w_m2,
                      const QuadtreeFigureStyle& style = {});

}  // namespace radrecon
