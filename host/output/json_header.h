// The fields every JSON output starts with, in one place: which program and version wrote it,
// the version of the output's own format (raised when a field changes meaning or goes, so
// `merge`, `plot` and users' scripts can tell), what kind of output it is and on which device.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace depthprec {

// 1: the first versioned format (rows of mts/table, records of the batch commands, lj).
constexpr int kJsonFormatVersion = 1;

nlohmann::json output_header(const std::string& kind, const std::string& device);

}  // namespace depthprec
