// The scene audit's per-pixel pass on the OpenCL device (kernels/audit.cl), built with the MTS
// variant's defines for the set-up's pair, so coverage, depth and storage are the MTS kernels'.
#pragma once

#include "host/audit/audit_reference.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

AuditPixels audit_device(OpenClRuntime& runtime, const Scene& scene, const AuditSetup& setup);

}  // namespace depthprec
