// cost's computation: per technique and format, its MTS over the scene's distances against the
// vertex bound, its Lapidous-Jiao error where it is an LJ buffer, its kernel cost per fragment
// pair, and what a GPU pays for it beyond its arithmetic.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "host/model/scene.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

// What a real GPU pays for the technique beyond its arithmetic (the technique table's words; a
// layered scene's layer count and mapping added).
std::string structural_cost(const Scene& s, Technique t);

// One record per technique x format: its MTS run, LJ error and (with timing) timing pass.
nlohmann::json cost_record(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                           bool timing);

}  // namespace depthprec
