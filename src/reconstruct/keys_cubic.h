#pragma once
// Keys' cubic convolution ("Cubic convolution interpolation for digital image processing", 1981):
// a local cubic interpolant of values on a regular grid, C1, exact for quadratics. On a cell edge
// it depends only on the nodes of that edge's grid line, so interpolants whose nodal values agree
// there are continuous across cells (bicubic with barriers, barrier_grid.h).

namespace radrecon {

/// Keys' cubic convolution (a = -1/2, the Catmull-Rom spline) along one axis of n >= 2 nodes,
/// unit spacing, at k + t (cell k, t in [0, 1]): the weights of nodes first..first + count - 1.
/// Inside, the 4 nodes k-1..k+2 with the kernel's weights; at an end, the missing node is Keys'
/// extrapolation f(-1) = 3 f(0) - 3 f(1) + f(2) (and its mirror image), folded into the
/// weights of the 3 nodes it uses; with 2 nodes, the linear extrapolations f(-1) = 2 f(0) - f(1)
/// and f(2) = 2 f(1) - f(0). All exact for quadratics (linear with 2 nodes), and at t = 0 or 1
/// only node k or k + 1 weighs (every folded-in weight then vanishes).
struct AxisWeights {
  int first, count;
  double w[4];
};

AxisWeights keys_weights(int n, int k, double t);

}  // namespace radrecon
