// Common to the MTS kernels: the layout's names at this program's GRID, and small helpers.
#define NV MTS_NV(GRID)
#define NT MTS_NT(GRID)
#define NE MTS_NE(GRID)
#define NE_PAD MTS_NE_PAD(GRID)
#define Q_YRANGE MTS_Q_YRANGE(GRID)
#define NV_PAD MTS_NV_PAD(GRID)
#define V_XW MTS_V_XW(GRID)
#define V_YW MTS_V_YW(GRID)
#define V_BAD_ROW MTS_V_BAD_ROW(GRID)
#define PLANE_STRIDE MTS_PLANE_STRIDE(GRID)

static inline float4 mat_vec(__global const float* m, float4 v) {
  float4 r;
  r.x = ((m[0] * v.x + m[1] * v.y) + m[2] * v.z) + m[3] * v.w;
  r.y = ((m[4] * v.x + m[5] * v.y) + m[6] * v.z) + m[7] * v.w;
  r.z = ((m[8] * v.x + m[9] * v.y) + m[10] * v.z) + m[11] * v.w;
  r.w = ((m[12] * v.x + m[13] * v.y) + m[14] * v.z) + m[15] * v.w;
  return r;
}

// any() of a 16-lane mask by halving ORs: PoCL expands any() into a test and branch per lane pair.
static inline int any16(int16 m) {
  const int8 m8 = m.lo | m.hi;
  const int4 m4 = m8.lo | m8.hi;
  const int2 m2 = m4.lo | m4.hi;
  return (m2.x | m2.y) < 0;
}
