// Encodes a contiguous run of binary32 bit patterns with one storage format, fixed at build time
// by -D defines (host/model/storage_format.cpp). Used by the exhaustive format proof and by
// `depthprec formats --on-device`.
//
// encode_range: one input per work-item through the scalar encoder, df_encode (the codes
// written). One call site, so the encoder is inlined and PoCL runs the work-group's work-items
// through it in SIMD lanes.
//
// encode16_differs: each work-item takes 16 of those inputs through the 16-lane encoders the MTS
// kernel uses (df_encode16, and df_encode16_unit for inputs in its domain [-0, 1]) and counts the
// lanes where either disagrees with the scalar code, so the proof covers all three. Where the
// 16-lane encoders are the scalar one lane by lane (df_encode16_is_scalar) there is nothing to
// compare and the host does not launch it.
#include "formats/depth_format.h"

__kernel void encode_range(const uint first_bits, const uint count, __global uint* restrict codes) {
  const uint i = get_global_id(0);
  if (i < count) codes[i] = df_encode(as_float(first_bits + i), DF_FORMAT_FROM_DEFINES());
}

__kernel void encode16_differs(const uint first_bits, const uint count,
                               __global const uint* restrict codes,
                               __global uint* restrict vector_differs) {
  const uint base = get_global_id(0) * 16u;
  const uint16 lane = (uint16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const uint16 bits = (uint16)(first_bits + base) + lane;
  const uint16 v = df_encode16(as_float16(bits), DF_FORMAT_FROM_DEFINES());
  const int16 unit_domain = bits <= (uint16)0x3f800000u || bits == (uint16)0x80000000u;
  const uint16 w =
      df_encode16_unit(as_float16(unit_domain ? bits : (uint16)0u), DF_FORMAT_FROM_DEFINES());
  uint16 c = (uint16)0u;
  if (base + 16u <= count) {
    c = vload16(0, codes + base);
  } else {
    for (uint k = 0; base + k < count; ++k) c[k] = codes[base + k];
  }
  const int16 bad = (base + lane < (uint16)count) & ((v != c) | (unit_domain & (w != c)));
  const uint16 one = as_uint16(bad) & (uint16)1u;
  const uint8 a = one.lo + one.hi;
  const uint4 b = a.lo + a.hi;
  const uint2 e = b.lo + b.hi;
  const uint differ = e.x + e.y;
  vector_differs[get_global_id(0)] = differ;
}
