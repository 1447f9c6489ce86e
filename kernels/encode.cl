// Encodes a contiguous run of binary32 bit patterns with one storage format, fixed at build time
// by -D defines (host/storage_format.cpp). Used by the exhaustive format proof and by
// `depthprec formats --on-device`. Each work-item takes 16 inputs through the scalar encoder
// (the codes written) and through the 16-lane encoder the MTS kernel uses; `vector_differs`
// counts the lanes where the two disagree, so the proof covers both.
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
  const uint16 bits = (uint16)(first_bits + base) +
                      (uint16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const uint16 v = df_encode16(as_float16(bits), DF_FORMAT_FROM_DEFINES());
  uint differ = 0;
  for (int k = 0; k < 16; ++k) differ += (base + (uint)k < count && v[k] != c[k]) ? 1u : 0u;
  vector_differs[get_global_id(0)] = differ;
}
