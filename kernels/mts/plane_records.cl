// What the kernels after the set-up read from a plane's records (kernels/mts/setup.cl writes
// them): the coverage certificate per band and per row, the records whose pixel boxes reach a
// band, and where plane A's records sit in the plane-A cache.
// Shared by the set-up program (kernels/mts_setup.cl) and the per-pixel ones (kernels/mts.cl,
// kernels/bias.cl).

// Every pixel of the band (or of the whole kernel) is owned by exactly one triangle, but for the
// rows band_bad_rows names.
static inline int band_covered(uint vf, uint band) {
  return (vf & MTS_V_COVERS) &&
         (band >= MTS_V_MAX_BANDS || !((vf >> (MTS_V_BAND_SHIFT + band)) & 1u));
}

// Every pixel of kernel row `row` of plane T (flags vf) is owned by exactly one triangle: the
// certificate of band_covered, down to the one row a vertex near a pixel centre spoils; in a plane
// with sliver triangles, whose bands are known but not their rows, only outside those bands.
static inline int row_covered(__global const float* T, uint vf, int row, uint band_rows) {
  __global const int16* bad = (__global const int16*)((__global const int*)T + V_BAD_ROW);
  int16 hit = (int16)0;
  for (int k = 0; k < NV_PAD / 16; ++k) hit |= bad[k] == (int16)row;
  return (vf & MTS_V_COVERS) &&
         (!(vf & MTS_V_SLIVERS) || band_covered(vf, (uint)row / band_rows)) && !any16(hit);
}

// The rows of [r0, r1) (at most 32) where a vertex of plane T lies near a pixel centre, as bits
// from r0: the only rows of a band_covered band whose pixels may not have exactly one owner.
static inline uint band_bad_rows(__global const float* T, int r0, int r1) {
  __global const int* bad = (__global const int*)T + V_BAD_ROW;
  uint rows = 0u;
  for (int v = 0; v < NV; ++v)
    if (bad[v] >= r0 && bad[v] < r1) rows |= 1u << (bad[v] - r0);
  return rows;
}

// The records of plane T from the first to the last quad row with bit qj set in `quad_rows`: a run
// from *first to before *end (none: 0, 0). A quad row's triangles fill its records in order, so
// the run holds every record of those quad rows.
static inline void quad_row_records(__global const float* T, uint quad_rows, int* first, int* end) {
  *first = 0;
  *end = 0;
  if (!quad_rows) return;
  const int lo = 31 - (int)clz(quad_rows & (~quad_rows + 1u)), hi = 31 - (int)clz(quad_rows);
  *first = Q_SLOTS * lo;
  *end = Q_SLOTS * hi + ((__global const int*)T)[Q_USED + hi];
}

// The records of plane T whose pixel boxes can reach kernel rows [r0, r1): those of the quad rows
// whose records' boxes reach them (Q_BOX_ROWS, set up from the boxes themselves), so every record
// outside the run has a box that misses the rows.
static inline void records_boxed_in_rows(__global const float* T, int r0, int r1, int* first,
                                         int* end) {
  uint quad_rows = 0u;
  for (int qj = 0; qj < GRID; ++qj) {
    const int2 rows = vload2(0, (__global const int*)T + Q_BOX_ROWS + 2 * qj);
    if (rows.s0 <= r1 - 1 && r0 <= rows.s1) quad_rows |= 1u << qj;
  }
  quad_row_records(T, quad_rows, first, end);
}

// Where plane A of (probe, visit) sits in the plane-A cache: a_slots holds per probe its slot and
// the frame its visit starts at (host/mts/mts_evaluator.h, frame order); each slot holds all
// frames_total frames of its distance; the launch covers visits first_frame.. of each probe. The
// start frame and first_frame + visit both lie below frames_total, so one subtraction wraps their
// sum (no division: mts_raster runs this per kernel row).
static inline uint a_plane(__global const uint* a_slots, uint probe, uint visit, uint first_frame,
                           uint frames_total) {
  const uint f = a_slots[2u * probe + 1u] + first_frame + visit;
  return a_slots[2u * probe] * frames_total + (f >= frames_total ? f - frames_total : f);
}
#define A_PLANE(pf) a_plane(a_slots, (pf) / frames, (pf) % frames, first_frame, frames_total)
