// The host side of interface/mts_kernel_args.h (and interface/audit_layout.h): per kernel, a struct
// of its buffers by name, and bind(), which sets them in the order the shared list gives and then
// the scalars' struct. A buffer left unset is an error naming it, not a kernel reading whatever was
// bound before.
#pragma once

#include <string>

#include "host/base/errors.h"
#include "host/runtime/cl.h"
#include "interface/audit_layout.h"
#include "interface/mts_kernel_args.h"

namespace depthprec {

namespace kernel_args {

inline void set_buffer(cl::Kernel& kernel, cl_uint index, const cl::Buffer* buffer,
                       const char* name) {
  if (!buffer)
    throw Error(ExitCode::internal, "kernel " + kernel.getInfo<CL_KERNEL_FUNCTION_NAME>() +
                                        ": buffer '" + name + "' not bound");
  kernel.setArg(index, *buffer);
}

}  // namespace kernel_args

#define DEPTHPREC_BUFFER_FIELD(type, name) const cl::Buffer* name = nullptr;
#define DEPTHPREC_SET_BUFFER(type, name) kernel_args::set_buffer(kernel, index++, b.name, #name);
#define DEPTHPREC_PLACEHOLDER(type, name) kernel_args::set_buffer(kernel, index++, &any, #name);
// Buffers: the kernel's buffers by name. bind: every argument. bind_placeholders: `any` for
// every buffer, for a launch whose work-items all return at once (PoCL's launch priming).
#define DEPTHPREC_KERNEL_BINDING(Buffers, LIST, Args)                                          \
  struct Buffers {                                                                             \
    LIST(DEPTHPREC_BUFFER_FIELD, DEPTHPREC_BUFFER_FIELD)                                       \
  };                                                                                           \
  inline void bind(cl::Kernel& kernel, const Buffers& b, const Args& args) {                   \
    cl_uint index = 0;                                                                         \
    LIST(DEPTHPREC_SET_BUFFER, DEPTHPREC_SET_BUFFER)                                           \
    kernel.setArg(index, args);                                                                \
  }                                                                                            \
  inline void bind_placeholders(cl::Kernel& kernel, const cl::Buffer& any, const Args& args) { \
    cl_uint index = 0;                                                                         \
    LIST(DEPTHPREC_PLACEHOLDER, DEPTHPREC_PLACEHOLDER)                                         \
    kernel.setArg(index, args);                                                                \
  }

DEPTHPREC_KERNEL_BINDING(MtsSetupBuffers, MTS_SETUP_BUFFERS, MtsSetupArgs)
DEPTHPREC_KERNEL_BINDING(MtsARowsBuffers, MTS_A_ROWS_BUFFERS, MtsARowsArgs)
DEPTHPREC_KERNEL_BINDING(MtsABandsBuffers, MTS_A_BANDS_BUFFERS, MtsABandsArgs)
DEPTHPREC_KERNEL_BINDING(MtsFrameBoundsBuffers, MTS_FRAME_BOUNDS_BUFFERS, MtsFrameBoundsArgs)
DEPTHPREC_KERNEL_BINDING(MtsRasterBuffers, MTS_RASTER_BUFFERS, MtsRasterArgs)
DEPTHPREC_KERNEL_BINDING(BiasSetupBuffers, BIAS_SETUP_BUFFERS, BiasSetupArgs)
DEPTHPREC_KERNEL_BINDING(BiasRowsBuffers, BIAS_ROWS_BUFFERS, BiasRowsArgs)
DEPTHPREC_KERNEL_BINDING(AuditPixelsBuffers, AUDIT_PIXELS_BUFFERS, AuditPixelsArgs)

#undef DEPTHPREC_KERNEL_BINDING
#undef DEPTHPREC_PLACEHOLDER
#undef DEPTHPREC_SET_BUFFER
#undef DEPTHPREC_BUFFER_FIELD

}  // namespace depthprec
