// Writing 16 triangle records at once: the register transpose that turns lanes into records, the
// edge arrays, the origin-referred planes of llvmpipe and softpipe, and each triangle's pixel box.

// 16 x 16 transpose: out[k] lane f = in[f] lane k, by swapping the off-diagonal b x b blocks of
// every 2b x 2b block for b = 8, 4, 2, 1 (each swap exchanges bit b of the row and column). The
// shuffles' lane lists are constants (__builtin_shufflevector), so each is one instruction: with
// masks computed at run time, PoCL's shuffle2 made the set-up slower than storing lane by lane.
#define SWAP_BLOCKS(m, b)                                          \
  _Pragma("unroll") for (int i = 0; i < 16; ++i) if (!(i & (b))) { \
    const uint16 a_ = m[i], c_ = m[i + (b)];                       \
    m[i] = __builtin_shufflevector(a_, c_, FIRST_##b);             \
    m[i + (b)] = __builtin_shufflevector(a_, c_, SECOND_##b);      \
  }
#define FIRST_8 0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19, 20, 21, 22, 23
#define SECOND_8 8, 9, 10, 11, 12, 13, 14, 15, 24, 25, 26, 27, 28, 29, 30, 31
#define FIRST_4 0, 1, 2, 3, 16, 17, 18, 19, 8, 9, 10, 11, 24, 25, 26, 27
#define SECOND_4 4, 5, 6, 7, 20, 21, 22, 23, 12, 13, 14, 15, 28, 29, 30, 31
#define FIRST_2 0, 1, 16, 17, 4, 5, 20, 21, 8, 9, 24, 25, 12, 13, 28, 29
#define SECOND_2 2, 3, 18, 19, 6, 7, 22, 23, 10, 11, 26, 27, 14, 15, 30, 31
#define FIRST_1 0, 16, 2, 18, 4, 20, 6, 22, 8, 24, 10, 26, 12, 28, 14, 30
#define SECOND_1 1, 17, 3, 19, 5, 21, 7, 23, 9, 25, 11, 27, 13, 29, 15, 31
static inline void transpose16(uint16* m) {
  SWAP_BLOCKS(m, 8)
  SWAP_BLOCKS(m, 4)
  SWAP_BLOCKS(m, 2)
  SWAP_BLOCKS(m, 1)
}
#undef SWAP_BLOCKS

// Triangle records slot[0 .. lanes - 1] from their fields (rec[field], a lane per record):
// transposed in registers, each record is two 16-word stores rather than 32 scattered ones.
static inline void write_records16(__global float* T, const int* slot, int lanes, uint16* rec) {
  transpose16(rec);
  transpose16(rec + 16);
  for (int k = 0; k < lanes; ++k) {
    __global uint* R = (__global uint*)T + slot[k] * MTS_TRI_STRIDE;
    vstore16(rec[k], 0, R);
    vstore16(rec[16 + k], 0, R + 16);
  }
}

// Their edges in the edge arrays (structure of arrays: edge e of record t at 3 t + e), from
// edges[array][e] (a lane per record): each array's 48 words interleaved in registers.
static inline void write_edges16(__global float* T, const int* slot, int lanes,
                                 uint16 edges[6][3]) {
  /* 16 records in a row (the grid's, without a clip stage): 3 stores per array */
  const int run = lanes == 16 && slot[15] == slot[0] + 15;
  for (int a = 0; a < 6; ++a) {
    /* word w = 16 h + j of out[h] is edge w % 3 of lane w / 3: edges 0 and 1 first, then 2 */
    const uint16 e0 = edges[a][0], e1 = edges[a][1], e2 = edges[a][2];
    const uint16 t0 =
        __builtin_shufflevector(e0, e1, 0, 16, 0, 1, 17, 1, 2, 18, 2, 3, 19, 3, 4, 20, 4, 5);
    const uint16 t1 =
        __builtin_shufflevector(e0, e1, 21, 5, 6, 22, 6, 7, 23, 7, 8, 24, 8, 9, 25, 9, 10, 26);
    const uint16 t2 = __builtin_shufflevector(e0, e1, 10, 11, 27, 11, 12, 28, 12, 13, 29, 13, 14,
                                              30, 14, 15, 31, 15);
    const uint16 out[3] = {
        __builtin_shufflevector(t0, e2, 0, 1, 16, 3, 4, 17, 6, 7, 18, 9, 10, 19, 12, 13, 20, 15),
        __builtin_shufflevector(t1, e2, 0, 21, 2, 3, 22, 5, 6, 23, 8, 9, 24, 11, 12, 25, 14, 15),
        __builtin_shufflevector(t2, e2, 26, 1, 2, 27, 4, 5, 28, 7, 8, 29, 10, 11, 30, 13, 14, 31)};
    __global uint* SA = (__global uint*)T + NT * MTS_TRI_STRIDE + a * NE_PAD;
    if (run) {
      for (int h = 0; h < 3; ++h) vstore16(out[h], 0, SA + 3 * slot[0] + 16 * h);
    } else {
      uint words[48];
      for (int h = 0; h < 3; ++h) vstore16(out[h], 0, words + 16 * h);
      for (int k = 0; k < lanes; ++k)
        for (int e = 0; e < 3; ++e) SA[3 * slot[k] + e] = words[3 * k + e];
    }
  }
}

#if PLANE_FORM != 0
// The depth and 1/w planes of a record referred to the framebuffer origin, as llvmpipe and softpipe
// refer them: the anchor vertex's value minus the gradients times its offset (xc, yc) from the
// origin pixel's centre; evaluated at integer pixel coordinates, so x0 = y0 = 1/2.
static inline void origin_planes16(uint16* rec, float16 xc, float16 yc, float16 d0, float16 dzdx,
                                   float16 dzdy, float16 q0, float16 dqdx, float16 dqdy) {
  rec[MTS_T_X0] = as_uint16((float16)0.5f);
  rec[MTS_T_Y0] = as_uint16((float16)0.5f);
  rec[MTS_T_D0] = as_uint16(d0 - (dzdx * xc + dzdy * yc));
  rec[MTS_T_DZDX] = as_uint16(dzdx);
  rec[MTS_T_DZDY] = as_uint16(dzdy);
  rec[MTS_T_Q0] = as_uint16(q0 - (dqdx * xc + dqdy * yc));
  rec[MTS_T_DQDX] = as_uint16(dqdx);
  rec[MTS_T_DQDY] = as_uint16(dqdy);
}

// v[i[lane]] per lane, i in 0..2.
static inline float16 pick16(const float16* v, int16 i) {
  return select(select(v[0], v[1], i == 1), v[2], i == 2);
}
#endif

// The kernel pixels (column i0..i1, row j0..j1: fields MTS_T_BOX .. MTS_T_BOX + 3) that a triangle
// may own: those whose centre lies within its bounding box widened by one pixel (an edge test can
// pass only within its rounding error outside the exact triangle). Empty when i0 > i1 or j0 > j1.
// The x extent is taken from the edges as the record stores them (anchor, anchor + direction).
static inline void pixel_boxes16(uint16* rec, const float16* ex, const float16* edx, float16 ymin,
                                 float16 ymax, float ox, float oy, int W, int H) {
  float16 xmin = (float16)INFINITY, xmax = (float16)-INFINITY;
  for (int e = 0; e < 3; ++e) {
    const float16 ax = ex[e], bx = ax + edx[e];
    xmin = fmin(xmin, fmin(ax, bx));
    xmax = fmax(xmax, fmax(ax, bx));
  }
  const int16 i0 = max(convert_int16(ceil(fmax(xmin - 1.0f - ox - 0.5f, -1.0f))), 0);
  const int16 i1 = min(convert_int16(floor(fmin(xmax + 1.0f - ox - 0.5f, (float)W))), W - 1);
  const int16 j0 = max(convert_int16(ceil(fmax(ymin - 1.0f - oy - 0.5f, -1.0f))), 0);
  const int16 j1 = min(convert_int16(floor(fmin(ymax + 1.0f - oy - 0.5f, (float)H))), H - 1);
  rec[MTS_T_BOX + 0] = as_uint16(i0);
  rec[MTS_T_BOX + 1] = as_uint16(i1);
  rec[MTS_T_BOX + 2] = as_uint16(j0);
  rec[MTS_T_BOX + 3] = as_uint16(j1);
}
