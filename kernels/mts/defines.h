/* The -D defines of the emulated pipeline's programs (kernels/mts.cl, kernels/mts_setup.cl,
 * kernels/mts_test.cl, kernels/bias.cl), the one list of them: what each means, and the check that
 * each is given, so a missing one is an #error rather than a silent 0. The host writes them
 * (host/runtime/kernel_variant.cpp); a test removes each in turn and expects this check.
 *
 * The set-up (kernels/mts_setup.cl defines MTS_SETUP_STAGE before including this) reads:
 *   GRID               quads per plane side (vertices (GRID+1)^2, triangles 2*GRID^2)
 *   DEPTH_FROM         0 projection, 1 vertex-stage log (Gilg eq. 5 or three.js's, by the probe
 *                      constant MTS_C_VERTEX_LOG), 2 fragment-stage depth (the set-up then
 *                      leaves d to the fragment stage)
 *   CONTRACT           1: the compiler may fuse a*b+c; 0: every operation rounds on its own
 *   PLANE_FORM         0: planes anchored at a vertex; 1: llvmpipe's, referred to the framebuffer
 *                      origin and evaluated with fma; 2: softpipe's, referred to the origin and
 *                      evaluated per 2x2 quad by increments, which is not monotone along a row, so
 *                      the shortcuts that assume it are off (host/model/scene.h PlaneForm)
 *   LLVMPIPE_LOG       1: the shaders' log is llvmpipe's (interface/llvmpipe_log.h); 0: OpenCL's
 *                      (the set-up's key leaves it 0 unless DEPTH_FROM is 1)
 *   CLIP_SLOTS         1: triangles as they are; MTS_CLIP_SLOTS: those crossing the viewport edge
 *                      clipped into fans as llvmpipe does (kernels/mts/setup/clip.cl)
 *   RELATIVE_TO_EYE    1: pipeline.transform relative_to_eye: each plane's matrix words are its
 *                      binary64 world matrix, the vertex stage forms Cesium's relative-to-eye
 *                      position (interface/relative_to_eye.h; needs cl_khr_fp64); 0: a binary32
 *                      model-view (or P * MV) as for every other transform
 * The per-pixel programs read those and:
 *   FRAG_DEPTH         with DEPTH_FROM 2: 1 linear, 2 w_buffer, 3 log, 4 three.js's log, 5
 *                      Cesium's log
 *   COMPARE_GREATER    1: GEQUAL (reversed mappings); 0: LEQUAL
 *   LOG_CODE_SLACK     codes a piece's end codes must clear a bound by under the library log's
 *                      error (fragment-stage log depth; 0 elsewhere)
 *   CACHE_A_CODES      1: the pixel loop reads plane A's codes from the plane-A cache
 *   FRAG_MEDIUMP       with DEPTH_FROM 2, the fragment shader's precision below binary32
 *                      (interface/binary16.h: 1 mediump, 2 the GLSL ES 1.00 highp minimum; 0
 *                      binary32; interface/mediump_fragment.h); its log's error then reaches a
 *                      step at that precision, which LOG_CODE_SLACK covers, and the gap
 *                      certificate is off
 *   ADVERSARY_CODES    1: unorm codes take an envelope's adversarial conversion
 *                      (interface/adversary.h), in each record's direction (MTS_T_ADVERSARY)
 *   ADVERSARY_CODE_SLACK  its slack: how far inside a code's half-interval it may not choose
 *   DF_*               the storage format (formats/depth_format.h; DF_KIND stands for them)
 * The vertex stage's choices are no defines: the depth range, the division, the composition of
 * the matrices, the fused forms of the matrix rows and the viewport, sub-pixel snapping and the
 * formula of vertex-stage log depth are probe constants (MTS_C_DEPTH_GL, MTS_C_FORMS,
 * MTS_C_SNAP_BITS, MTS_C_VERTEX_LOG in interface/mts_layout.h), read
 * by that stage alone, so pairs that differ in them alone share one program. */
#if !defined(GRID) || !defined(DEPTH_FROM) || !defined(CONTRACT) || !defined(PLANE_FORM) || \
    !defined(LLVMPIPE_LOG) || !defined(CLIP_SLOTS) || !defined(RELATIVE_TO_EYE)
#error \
    "the emulated pipeline needs GRID, DEPTH_FROM, CONTRACT, PLANE_FORM, LLVMPIPE_LOG, CLIP_SLOTS and RELATIVE_TO_EYE (kernels/mts/defines.h)"
#endif
#ifndef MTS_SETUP_STAGE
#if !defined(FRAG_DEPTH) || !defined(COMPARE_GREATER) || !defined(LOG_CODE_SLACK) ||          \
    !defined(CACHE_A_CODES) || !defined(ADVERSARY_CODES) || !defined(ADVERSARY_CODE_SLACK) || \
    !defined(FRAG_MEDIUMP) || !defined(DF_KIND)
#error \
    "the per-pixel pipeline needs FRAG_DEPTH, COMPARE_GREATER, LOG_CODE_SLACK, CACHE_A_CODES, ADVERSARY_CODES, ADVERSARY_CODE_SLACK, FRAG_MEDIUMP and the DF_* format defines (kernels/mts/defines.h)"
#endif
#endif
