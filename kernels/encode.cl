// Encodes a contiguous run of binary32 bit patterns with one storage format, fixed at build time
// by -D defines (host/storage_format.cpp). Used by the exhaustive format proof and by
// `depthprec formats --device-check`.
#include "formats/depth_format.h"

__kernel void encode_range(const uint first_bits, __global uint* restrict codes) {
  const uint i = get_global_id(0);
  codes[i] = df_encode(as_float(first_bits + i), DF_FORMAT_FROM_DEFINES());
}
