// Runs formats/depth_format.h's encoder on the OpenCL device (kernels/encode.cl), specialised
// for one format by -D defines.
#pragma once

#include <cstdint>
#include <vector>

#include "host/model/storage_format.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec {

// Codes of the binary32 bit patterns first_bits .. first_bits + count - 1, into out (resized).
// Returns how many of them the kernels' 16-lane encoder (df_encode16) coded differently from the
// scalar one: 0 unless the vector path is wrong.
uint64_t device_encode_range(OpenClRuntime& rt, const StorageFormat& f, uint32_t first_bits,
                             uint32_t count, std::vector<uint32_t>& out);

// Codes of arbitrary values (one launch per call; for spot checks, not bulk work).
std::vector<uint32_t> device_encode(OpenClRuntime& rt, const StorageFormat& f,
                                    const std::vector<float>& values);

}  // namespace depthprec
