// Common to the MTS kernels: the layout's names at this program's GRID, and small helpers.
#define NV MTS_NV(GRID)
#define NT0 (2 * GRID * GRID) /* the grid's triangles; NT0 * CLIP_SLOTS records */
#define NT MTS_NT(GRID, CLIP_SLOTS)
#define NE MTS_NE(GRID, CLIP_SLOTS)
#define NE_PAD MTS_NE_PAD(GRID, CLIP_SLOTS)
#define Q_YRANGE MTS_Q_YRANGE(GRID, CLIP_SLOTS)
#define Q_USED MTS_Q_USED(GRID, CLIP_SLOTS)
#define Q_BOX_ROWS MTS_Q_BOX_ROWS(GRID, CLIP_SLOTS)
#define Q_SLOTS (2 * GRID * CLIP_SLOTS) /* records per quad row */
#define NV_PAD MTS_NV_PAD(GRID)
#define V_BAD_ROW MTS_V_BAD_ROW(GRID, CLIP_SLOTS)
#define PLANE_STRIDE MTS_PLANE_STRIDE(GRID, CLIP_SLOTS)

// m * v row by row, fused (F_VERTEX_FMA) or not (host/model/frame_setup.h mat_row_dot): a
// computed vector v, or a plane's object position (x, y, 0, 1), whose constant z and w a shader
// compiler folds away (object_row_dot).
static inline float mat_row(__global const float* m, float4 v, int fused) {
  return fused ? fma(m[3], v.w, fma(m[2], v.z, fma(m[1], v.y, m[0] * v.x)))
               : ((m[0] * v.x + m[1] * v.y) + m[2] * v.z) + m[3] * v.w;
}

static inline float obj_row(__global const float* m, float4 obj, int fused) {
  return fused ? fma(m[1], obj.y, fma(m[0], obj.x, m[3])) : mat_row(m, obj, 0);
}

static inline float4 mat_vec(__global const float* m, float4 v, int fused) {
  return (float4)(mat_row(m, v, fused), mat_row(m + 4, v, fused), mat_row(m + 8, v, fused),
                  mat_row(m + 12, v, fused));
}

static inline float4 obj_vec(__global const float* m, float4 obj, int fused) {
  return (float4)(obj_row(m, obj, fused), obj_row(m + 4, obj, fused), obj_row(m + 8, obj, fused),
                  obj_row(m + 12, obj, fused));
}

// The shaders' natural log, of one value and of 16 (LLVMPIPE_LOG, kernels/llvmpipe_log.h).
#if LLVMPIPE_LOG
DP_LLVMPIPE_LOG_DEFINE(shader_log, float, as_uint, as_float, convert_float, fma)
DP_LLVMPIPE_LOG_DEFINE(shader_log16, float16, as_uint16, as_float16, convert_float16, fma)
#else
#define shader_log log
#define shader_log16 log
#endif

// any() of a 16-lane mask by halving ORs: PoCL expands any() into a test and branch per lane pair.
static inline int any16(int16 m) {
  const int8 m8 = m.lo | m.hi;
  const int4 m4 = m8.lo | m8.hi;
  const int2 m2 = m4.lo | m4.hi;
  return (m2.x | m2.y) < 0;
}
