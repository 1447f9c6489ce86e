/* Sub-pixel snapping (pipeline.snap, docs/spec.md 2): a window x or y moved to the nearest point
 * of the grid of 2^-bits pixel, half to even, as a rasterizer with that many fractional bits of
 * sub-pixel precision stores its vertices (Direct3D 10+ requires 8, and Vulkan and GL
 * implementations use 4 or 8); bits = 0 leaves it alone. One source for the kernels and the host
 * reference. Exact in binary32: the scaling by a power of two and rint are exact, and from
 * 2^(23 - bits) on every binary32 already lies on the grid, which also keeps inf and NaN. */
#ifndef DP_SNAP_H
#define DP_SNAP_H

#define DP_SNAP_WINDOW_DEFINE(NAME, FABS, RINT)                        \
  static inline float NAME(float x, int bits) {                        \
    if (bits <= 0 || !(FABS(x) < (float)(1 << (23 - bits)))) return x; \
    const float grid = (float)(1 << bits);                             \
    return RINT(x * grid) / grid;                                      \
  }

#endif
