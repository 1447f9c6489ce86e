// `depthprec shadow`'s output from its header and cascade records (host/shadow/shadow_run.h):
// text and Markdown as two captioned tables (the biases per cascade, the engines' settings), CSV
// as one row per cascade and engine, JSON as the records themselves.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace depthprec {

std::string render_shadow_output(const nlohmann::json& header,
                                 const std::vector<nlohmann::json>& records,
                                 const std::string& format);

}  // namespace depthprec
