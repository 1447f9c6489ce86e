/* The binary layout shared by the MTS kernels (kernels/mts.cl and its parts, kernels/mts_exact.cl)
 * and the host (host/mts/mts_evaluator.cpp, host/model/frame_setup.cpp), one source for both as
 * interface/lj_formulas.h is for the LJ formulas: the records of a plane, of a probe's constants,
 * of a cached row and band of plane A, of mts_frame_bounds' verdicts, and the bits of a row's
 * result word. Valid C++ and OpenCL C. The plane record depends on the grid (quads per plane side):
 * MTS_PLANE_STRIDE(grid, slots) for the host, PLANE_STRIDE (GRID and CLIP_SLOTS from -D) in the
 * kernels. Each of the grid's 2 grid^2 triangles owns `slots` triangle records: 1, or
 * MTS_CLIP_SLOTS when the pipeline clips triangles at the viewport edge as llvmpipe does
 * (pipeline.clip), whose fan of at most 5 triangles fills its slots in order. */
#ifndef DEPTHPREC_MTS_LAYOUT_H
#define DEPTHPREC_MTS_LAYOUT_H

/* A plane record: NT triangle records of MTS_TRI_STRIDE floats, then its 3*NT edges as arrays
 * (structure of arrays, padded to a multiple of 16) so a row can place all edge boundaries 16 at
 * a time. */
#define MTS_CLIP_SLOTS 5 /* a triangle clipped by the four x, y planes has at most 7 vertices */
#define MTS_NV(g) (((g) + 1) * ((g) + 1))
#define MTS_NT(g, s) (2 * (g) * (g) * (s))
#define MTS_TRI_STRIDE 32
#define MTS_NE(g, s) (3 * MTS_NT(g, s))
#define MTS_NE_PAD(g, s) ((MTS_NE(g, s) + 15) / 16 * 16)
#define MTS_E_AX 0
#define MTS_E_AY 1
#define MTS_E_DX 2
#define MTS_E_DY 3
#define MTS_E_DXDY 4
#define MTS_E_BITS 5 /* uint: bit 0 negate, bit 1 owns, then the ids of the edge's two vertices */
/* 15 bits each, in the triangle's order: which vertices (b_keeps_a_edges) */
#define MTS_E_ID_SHIFT 2
/* Then each row of quads' y-range (grid pairs ymin, ymax), then (grid ints) how many triangle
 * records it uses from its first, 2 grid slots qj: the triangles a kernel row can meet are those
 * of the quad rows whose range holds it, a run of indices. A quad row's triangles fill its
 * records in order, a clipped one's fan in place of it, so the order is the grid's. */
#define MTS_Q_YRANGE(g, s) (MTS_NT(g, s) * MTS_TRI_STRIDE + 6 * MTS_NE_PAD(g, s))
#define MTS_NV_PAD(g) ((MTS_NV(g) + 15) / 16 * 16)
#define MTS_Q_USED(g, s) (MTS_Q_YRANGE(g, s) + 2 * (g))
/* Then per row of quads (grid int pairs) the first and last kernel row its records' pixel boxes
 * reach (pixel_boxes16; first > last: none), so a band's code bounds visit only the quad rows
 * that can meet it. */
#define MTS_Q_BOX_ROWS(g, s) (MTS_Q_USED(g, s) + (g))
/* Then, from a multiple of 16 ints on (so they load as aligned int16, and every plane record
 * starts at one), per vertex the kernel row of the pixel centre it lies near (int; -1: none, or
 * padding): the rows covers_kernel's certificate does not hold for (row_covered). */
#define MTS_V_BAD_ROW(g, s) ((MTS_Q_BOX_ROWS(g, s) + 2 * (g) + 15) / 16 * 16)
#define MTS_PLANE_STRIDE(g, s) (MTS_V_BAD_ROW(g, s) + MTS_NV_PAD(g))

/* A triangle record's bits (MTS_T_BITS): edge e's function is negated (it runs from its
 * lower-id vertex, against the triangle's orientation), edge e is owned (a pixel centre on it is
 * covered: a top or left edge), and the triangle rasterises at all (non-zero finite area). */
#define MTS_BIT_NEGATE(e) (1u << (e))
#define MTS_BIT_OWNS(e) (8u << (e))
#define MTS_BIT_NEGATE_ALL 7u
#define MTS_BIT_VALID 64u

/* Edge e at pixel centre (px, py): its function from the edge's lower-id vertex (ax, ay) along
 * (dx, dy), and whether it passes once negated as its bit says (positive, or zero on an edge the
 * triangle owns; `owns` 0 / 1 for scalars, 0 / -1 for vector masks). One expression for the host's
 * covers, the kernels' coverage and the audit, scalar or vector, so all agree on every pixel. */
#define MTS_EDGE_FUNCTION(ax, ay, dx, dy, px, py) ((dx) * ((py) - (ay)) - (dy) * ((px) - (ax)))
#define MTS_EDGE_PASSES(E, owns) (((E) > 0.0f) | (((E) == 0.0f) & (owns)))

/* Triangle record offsets */
#define MTS_T_EDGES 0 /* 3 x (ax, ay, dx, dy) */
#define MTS_T_BITS 12 /* uint: MTS_BIT_NEGATE(e), MTS_BIT_OWNS(e), MTS_BIT_VALID */
#define MTS_T_X0 13
#define MTS_T_Y0 14
#define MTS_T_D0 15
#define MTS_T_DZDX 16
#define MTS_T_DZDY 17
#define MTS_T_Q0 18
#define MTS_T_DQDX 19
#define MTS_T_DQDY 20
#define MTS_T_YMIN 21
#define MTS_T_YMAX 22
#define MTS_T_DXDY 23 /* 3 x dx/dy per edge: a first guess of where a row crosses it */
#define MTS_T_BIAS 26 /* the triangle's depth bias (kernels/bias.cl only) */
/* kernels/mts.cl's use of the same word: the direction an envelope's adversary moves the plane's
 * stored codes (interface/adversary.h): +1 up, -1 down, 0 none; depth bias takes no envelope */
#define MTS_T_ADVERSARY 26
/* the largest |window depth| of its vertices (the float rule of depth bias) */
#define MTS_T_ZMAX 27
#define MTS_T_BOX 28 /* int4: the kernel pixels the triangle may own (setup.cl pixel_boxes16) */

/* A probe's constants (host/model/frame_setup.h ProbeConstants::packed): P, then these. */
#define MTS_PROBE_STRIDE 44
#define MTS_C_NEAR 16
#define MTS_C_FAR 17
#define MTS_C_RANGE 18
#define MTS_C_LOGK 19
#define MTS_C_LOGL 20
/* kernels/bias.cl: the probe's bias (interface/bias_formula.h depth_bias's units_term, factor,
 * clamp), signed as the application sets them */
#define MTS_C_BIAS_UNITS 21
#define MTS_C_BIAS_FACTOR 22
#define MTS_C_BIAS_CLAMP 23
/* The vertex stage's choices, read by it alone (kernels/mts/setup.cl), so they are constants of
 * the probe rather than defines and every choice runs in one program. */
#define MTS_C_DEPTH_GL 24 /* 1: OpenGL's depth range, d = z_ndc / 2 + 1/2; 0: d = z_ndc */
#define MTS_C_FORMS 25    /* the arithmetic forms, F_* bits */
/* window x, y snapped to 2^-n pixel (interface/snap.h); 0: as computed */
#define MTS_C_SNAP_BITS 26
/* The engines' log depth constants, computed in binary64 as their JavaScript does and uploaded as
 * binary32 (docs/spec.md 3): three.js's logDepthBufFC = 2 / log2(far + 1); Cesium's
 * czm_farDepthFromNearPlusOne = far - near + 1 and czm_oneOverLog2FarDepthFromNearPlusOne. */
#define MTS_C_THREEJS_FC 27
#define MTS_C_CESIUM_FAR1 28
#define MTS_C_CESIUM_INV_LOG2 29
/* The vertex stage's log depth (DEPTH_FROM 1): MTS_VERTEX_LOG_GILG, z_clip from ln(k w + 1) / L
 * (log_vertex); MTS_VERTEX_LOG_THREEJS, three.js's log2(max(1e-6, w + 1)) * FC - 1
 * (log_threejs_vertex). */
#define MTS_C_VERTEX_LOG 30
#define MTS_VERTEX_LOG_GILG 0
#define MTS_VERTEX_LOG_THREEJS 1
/* Where the scene sits away from the world origin (pipeline.transform, docs/spec.md 2): the view
 * matrix's translation, added after the model matrix under MTS_F_VIEW_TRANSLATE (absolute,
 * compose separate), and the eye's relative-to-eye parts (interface/relative_to_eye.h), read when
 * the set-up program is built with RELATIVE_TO_EYE 1. */
#define MTS_C_VIEW_X 31     /* then y, z */
#define MTS_C_EYE_HIGH_X 34 /* then y, z */
#define MTS_C_EYE_LOW_X 37  /* then y, z */
/* An envelope's adversary (pipeline.envelope, interface/adversary.h), read by the set-up alone:
 * the direction this plane's window depth moves (+1 up, -1 down, 0: no adversary; plane A's
 * towards the far side of the depth test, plane B's towards the near side), whether its
 * reciprocal of w takes the faithful rounding in that direction, and the relative interpolation
 * error it takes in that direction. */
#define MTS_C_ADV_DEPTH 40
#define MTS_C_ADV_RECIPROCAL 41
#define MTS_C_ADV_INTERPOLATION 42
/* z_clip / w_clip correctly rounded; else z_clip * fl(1 / w_clip) */
#define MTS_F_DIVIDE_EXACT 1u
/* the host uploads P * MV, one product per vertex; else P (MV v) */
#define MTS_F_COMPOSE_PREMULT 2u
#define MTS_F_VIEWPORT_FMA 4u    /* window coordinates as fma(ndc, scale, translate) */
#define MTS_F_VERTEX_FMA 8u      /* matrix rows fused as llvmpipe's shader fuses them (mat_row) */
#define MTS_F_VIEW_TRANSLATE 16u /* eye = model * v + view translation, in binary32 */
#define MTS_F_MEDIUMP 32u        /* the vertex shader in binary16 (interface/binary16.h) */
#define MTS_F_ES2_HIGHP 64u      /* ... at the GLSL ES 1.00 highp minimum (the same header) */
#define MTS_MAT_STRIDE 16        /* a 4x4 matrix, row-major */
/* Relative to eye, a plane's binary64 world matrix instead: 16 doubles in 32 floats' place */
#define MTS_WORLD_MAT_STRIDE 32

/* A plane's flags (vflags): non-finite vertices; the coverage certificate (covers_kernel). */
#define MTS_V_NONFINITE 1u
#define MTS_V_COVERS 2u
#define MTS_V_SLIVERS 4u /* bands left out of the certificate for a sliver triangle (setup.cl) */
#define MTS_V_BAND_SHIFT 8
#define MTS_V_MAX_BANDS 24u

/* Per kernel row of one (probe, frame): the result word. The number of fragment pairs evaluated
 * sits above the bits. kernels/mts_exact.cl writes the same word. */
#define MTS_R_FIGHT 1u
#define MTS_R_CLIPPED 2u
#define MTS_R_NONFINITE 4u
#define MTS_R_UNCOVERED 8u
#define MTS_R_BOUNDS 16u /* the row's band was decided clean from code bounds, not rasterised */
#define MTS_R_REUSED 32u /* plane B's coverage of the row was plane A's (coverage_margin) */
#define MTS_R_CHORDS 64u /* mts_exact: pixels decided clean from plane B's chords (CHORDS) */
#define MTS_R_COUNT_SHIFT 8

/* Plane A does not depend on the separation, so the host sets it up once per (distance, frame)
 * for every probe of the distance (host/mts/mts_evaluator.cpp, the plane-A cache): its triangles,
 * its code bounds per band, and per kernel row its coverage segments and coverage margin. */
/* segments a cached row holds; a row with more is computed where it is used */
#define MTS_MAXC 24
#define MTS_RW_N 0
#define MTS_RW_MARGIN 1
#define MTS_RW_X 2
#define MTS_RW_T (MTS_RW_X + MTS_MAXC + 1)
#define MTS_ROW_WORDS (MTS_RW_T + MTS_MAXC)
/* kernel rows of one plane per work-item of mts_a_rows: consecutive rows meet the same triangle
 * records, whose comparison with the reference distance's a work-item then makes once */
#define MTS_A_ROWS_PER_ITEM 8
/* mts_a_rows' work-items per plane: its KH kernel rows in groups of MTS_A_ROWS_PER_ITEM */
#define MTS_A_ROW_GROUPS(KH) (((KH) + MTS_A_ROWS_PER_ITEM - 1) / MTS_A_ROWS_PER_ITEM)
/* Per band of cached plane A (mts_a_bands): code bounds lo, hi, bad, then the gap range */
#define MTS_BW_GAP_LO 3
#define MTS_BW_GAP_HI 4
#define MTS_BAND_WORDS 5
/* CACHE_A_CODES (host/runtime/kernel_variant.h): plane A's stored code at every pixel of a cached
 * row, so the pixel loop evaluates plane B only; rows of kernel_w + 16 codes (a 16-lane store
 * past a segment's end lands in the next segment or the padding). */
#define MTS_CODE_ROW_PAD 16

/* mts_frame_bounds' words per band of a (probe, frame), read by mts_raster: the verdict (D_*, the
 * bits MTS_D_MASK) with bit MTS_DV_ORIENTED: plane B's edges that the band's rows can meet join A's
 * vertices with A's orientation (b_keeps_a_edges); how far they lie from A's (b_moved_from_a,
 * a float; infinite in a band decided clean, where mts_raster does not ask); and the rows the
 * verdict leaves out, a bit per row from the band's first (band_bad_rows of A and B): a vertex
 * near a pixel centre there, so they are rasterised as MTS_D_RASTER rows whatever the verdict. */
#define MTS_DW_VERDICT 0
#define MTS_DW_MOVED 1
#define MTS_DW_BAD_ROWS 2
#define MTS_DECIDED_WORDS 3
#define MTS_D_MASK 3u
#define MTS_DV_ORIENTED 4u
#define MTS_D_RASTER 0u /* rasterise, deciding pieces from their end codes first */
#define MTS_D_CLEAN 1u  /* clean from code bounds or the gap certificate: not rasterised */
#define MTS_D_INSIDE 2u /* rasterise straight through the pixel loop: see mts_frame_bounds */
/* MTS_D_INSIDE, and every depth of plane A at or above df_order_exact_from */
#define MTS_D_ORDERED 3u

/* A fragment's status (mts_codes, for the tests; host/mts/reference_pipeline.cpp likewise) */
#define MTS_S_OK 0
#define MTS_S_CLIPPED 1
#define MTS_S_NONFINITE 2
#define MTS_S_UNCOVERED 3

#endif
