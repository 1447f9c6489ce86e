// The set-up of a plane, by stage, each part using the ones above it (included by
// kernels/mts_setup.cl and kernels/bias.cl).
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#include "interface/adversary.h" /* an envelope's adversary, shared with the host reference */
DP_ADV_RECIPROCAL_DEFINE(adv_reciprocal, fma, nextafter)
// clang-format off
#include "kernels/mts/setup/certificate.cl" /* which kernel pixels the plane provably covers */
#include "kernels/mts/setup/records.cl"     /* 16 triangle records written at once; pixel boxes */
#include "kernels/mts/setup/triangles.cl"   /* the triangle set-up, 16 at a time */
#include "kernels/mts/setup/vertex.cl"      /* vertex stage, divide, window transform, snapping */
#include "kernels/mts/setup/clip.cl"        /* llvmpipe's clip stage: fans at the viewport edge */
#include "kernels/mts/setup/plane.cl"       /* one plane in one frame, every stage in order */
// clang-format on
