#include "host/output/json_header.h"

#include "host/base/version.h"

namespace depthprec {

nlohmann::json output_header(const std::string& kind, const std::string& device) {
  return {{"program", "depthprec"},
          {"version", kVersion},
          {"format_version", kJsonFormatVersion},
          {"kind", kind},
          {"device", device}};
}

}  // namespace depthprec
