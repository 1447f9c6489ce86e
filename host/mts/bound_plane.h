// How far any implementation of the bound model can store a plane's depth from its exact value at
// any kernel pixel, over the whole rotation cube (docs/bound.md), term by
// term: each term is written beside the binary32 arithmetic it bounds in bound_plane.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "host/mts/bound_geometry.h"

namespace depthprec::bound {

// The terms name the freedoms a user can ask of a driver or a shader (docs/mts.md): a row's
// bound_by is the largest. A model's freedom that the default model does not take (a reciprocal
// within 1 ulp, snapping, an interpolation tolerance) is a term of its own, zero elsewhere.
enum Term {
  kVertex,      // the vertex stage's rows (and the matrices' entries) moving a vertex in eye space
  kClip,        // the clip coordinates' rounding: P's rows, llvmpipe's clip stage
  kDivide,      // the divide by w and the viewport transform, the reciprocal correctly rounded
  kReciprocal,  // what a reciprocal within 1 ulp (d3d11) adds to them
  kPosition,    // window x and y errors through the plane's depth gradient
  kSnap,        // sub-pixel snapping of window x and y through the gradient
  kSetup,       // the depth plane's gradients rounded, over the distance to the pixel
  kInterpolation,           // evaluating (or stepping) the plane at the pixel
  kInterpolationTolerance,  // an API's stated interpolation error (vulkan_min: 10^-5)
  kShader,                  // a fragment shader's own arithmetic and its log
  kStorage,                 // the conversion to the stored code
  kTermCount
};
const char* term_name(int term);

struct DepthError {
  std::array<double, kTermCount> term{};
  double total() const;
};

// Bound on |computed depth - exact depth| at any pixel centre of the kernel for plane g.
DepthError depth_error(const RowModel& m, const PlaneGeometry& g);

// The least and the greatest exact depth the plane has at a kernel pixel (the ends of the pixels'
// range of w, the map being monotone).
struct PixelDepths {
  double lo, hi;
  double magnitude() const { return std::max(std::fabs(lo), std::fabs(hi)); }
};
PixelDepths pixel_depths(const RowModel& m, const PlaneGeometry& g);

// The largest |d value / d pixel| of the plane's interpolated value (window depth, or 1/w for
// fragment-stage depth) along x and along y, over the cube.
std::array<double, 2> window_gradient(const RowModel& m, const PlaneGeometry& g);

}  // namespace depthprec::bound
