// Encodes a contiguous run of binary32 bit patterns with one storage format, fixed at build time
// by -D defines (host/model/storage_format.cpp). Used by the exhaustive format proof and by
// `depthprec formats --on-device`. Each work-item takes 16 inputs through the scalar encoder
// (the codes written) and through the 16-lane encoders the MTS kernel uses (df_encode16, and
// df_encode16_unit for inputs in its domain [-0, 1]); `vector_differs` counts the lanes where
// either disagrees with the scalar code, so the proof covers all three. Where the 16-lane encoders
// are the scalar one lane by lane (df_encode16_is_scalar) there is nothing to compare, and the
// float formats' proof runs a third as long.
#include "formats/depth_format.h"

__kernel void encode_range(const uint first_bits, const uint count, __global uint* restrict codes,
                           __global uint* restrict vector_differs) {
  const uint base = get_global_id(0) * 16u;
  uint c[16];
  for (int k = 0; k < 16; ++k) {
    const uint i = base + (uint)k;
    c[k] = df_encode(as_float(first_bits + i), DF_FORMAT_FROM_DEFINES());
    if (i < count) codes[i] = c[k];
  }
  if (df_encode16_is_scalar(DF_FORMAT_FROM_DEFINES())) {
    vector_differs[get_global_id(0)] = 0u;
    return;
  }
  const uint16 bits =
      (uint16)(first_bits + base) + (uint16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const uint16 v = df_encode16(as_float16(bits), DF_FORMAT_FROM_DEFINES());
  const int16 unit_domain = bits <= (uint16)0x3f800000u || bits == (uint16)0x80000000u;
  const uint16 w =
      df_encode16_unit(as_float16(unit_domain ? bits : (uint16)0u), DF_FORMAT_FROM_DEFINES());
  uint differ = 0;
  for (int k = 0; k < 16; ++k)
    differ +=
        (base + (uint)k < count && (v[k] != c[k] || (unit_domain[k] && w[k] != c[k]))) ? 1u : 0u;
  vector_differs[get_global_id(0)] = differ;
}
