#include "host/base/json_number.h"

#include <fmt/format.h>

#include <cmath>

#include "host/base/errors.h"

namespace depthprec {

nlohmann::json json_number(double v) {
  if (std::isfinite(v)) return v;
  if (std::isnan(v)) return "nan";
  return v > 0 ? "inf" : "-inf";
}

double number_from_json(const nlohmann::json& v, const std::string& what) {
  if (v.is_number()) return v.get<double>();
  if (v == "inf") return INFINITY;
  if (v == "-inf") return -INFINITY;
  if (v == "nan") return NAN;
  throw InputError(
      fmt::format("'{}' must be a number, \"inf\", \"-inf\" or \"nan\", not {}", what, v.dump()));
}

}  // namespace depthprec
