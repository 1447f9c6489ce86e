// pipelines' computation: a pair's MTS at every distance under each way the host can build and
// apply the matrices (matrix_precision x compose).
#pragma once

#include <nlohmann/json.hpp>

#include "host/model/scene.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

struct PipelineVariant {
  const char* name;
  MatrixPrecision precision;
  Compose compose;
};
inline const PipelineVariant kPipelineVariants[] = {
    {"float/separate", MatrixPrecision::single, Compose::separate},
    {"float/premultiplied", MatrixPrecision::single, Compose::premultiplied},
    {"double/separate", MatrixPrecision::binary64, Compose::separate},
    {"double/premultiplied", MatrixPrecision::binary64, Compose::premultiplied}};

// One record per pair: the MTS at every distance under each variant.
nlohmann::json pair_record(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair);

}  // namespace depthprec
