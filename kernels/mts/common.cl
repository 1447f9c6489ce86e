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
/* a plane's words in the set-up's matrix buffer (host/model/frame_setup.h append_plane_words) */
#if RELATIVE_TO_EYE
#define PLANE_MATRIX_WORDS MTS_WORLD_MAT_STRIDE
#else
#define PLANE_MATRIX_WORDS MTS_MAT_STRIDE
#endif

// A kernel's buffers as parameters, from its list in interface/mts_kernel_args.h.
#define MTS_ARG_IN(type, name) __global const type *restrict name,
#define MTS_ARG_OUT(type, name) __global type *restrict name,

// The lane indices of a 16-lane vector.
#define LANES ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))

// m * v row by row for 16 vectors in lanes, fused (MTS_F_VERTEX_FMA) or not
// (host/model/vertex_stage.h mat_row_dot): a computed vector, or a plane's object position (x, y,
// 0, 1), whose constant z and w a shader compiler folds away (obj_row16).
typedef struct {
  float16 x, y, z, w;
} vec4x16_t;

static inline float16 mat_row16(__global const float* m, vec4x16_t v, int fused) {
  return fused
             ? fma((float16)m[3], v.w, fma((float16)m[2], v.z, fma((float16)m[1], v.y, m[0] * v.x)))
             : ((m[0] * v.x + m[1] * v.y) + m[2] * v.z) + m[3] * v.w;
}

static inline float16 obj_row16(__global const float* m, vec4x16_t obj, int fused) {
  return fused ? fma((float16)m[1], obj.y, fma((float16)m[0], obj.x, (float16)m[3]))
               : mat_row16(m, obj, 0);
}

// m * v (object: v is an object position, obj_row16).
static inline vec4x16_t mat_vec16(__global const float* m, vec4x16_t v, int fused, int object) {
  vec4x16_t r;
  r.x = object ? obj_row16(m, v, fused) : mat_row16(m, v, fused);
  r.y = object ? obj_row16(m + 4, v, fused) : mat_row16(m + 4, v, fused);
  r.z = object ? obj_row16(m + 8, v, fused) : mat_row16(m + 8, v, fused);
  r.w = object ? obj_row16(m + 12, v, fused) : mat_row16(m + 12, v, fused);
  return r;
}

// The shaders' natural log and log2, of one value and of 16 (LLVMPIPE_LOG,
// interface/llvmpipe_log.h).
#if LLVMPIPE_LOG
DP_LLVMPIPE_LOG_DEFINE(shader_log2, shader_log, float, as_uint, as_float, convert_float, fma)
DP_LLVMPIPE_LOG_DEFINE(shader_log2_16, shader_log16, float16, as_uint16, as_float16,
                       convert_float16, fma)
#else
#define shader_log log
#define shader_log16 log
#define shader_log2 log2
#define shader_log2_16 log2
#endif

// any() of a 16-lane mask by halving ORs: PoCL expands any() into a test and branch per lane pair.
static inline int any16(int16 m) {
  const int8 m8 = m.lo | m.hi;
  const int4 m4 = m8.lo | m8.hi;
  const int2 m2 = m4.lo | m4.hi;
  return (m2.x | m2.y) < 0;
}
