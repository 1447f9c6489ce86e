#include "host/analysis/lj_tables.h"

#include <fmt/format.h>

#include <algorithm>

#include "host/base/json_number.h"
#include "host/model/storage_format.h"

namespace depthprec {

std::vector<std::string> split_formats(int bits) {
  std::vector<std::string> out = {fmt::format("unorm{}", bits)};
  for (int e = 1; e <= std::min(8, bits - 1); ++e)
    out.push_back(fmt::format("e{}m{}", e, bits - e));
  return out;
}

std::vector<Ranked> sweep(OpenClRuntime& rt, const LjConfig& c, int bits) {
  std::vector<Ranked> out;
  int e = 0;
  for (const auto& name : split_formats(bits))
    out.push_back({name, e++, lj_average_error_device(rt, c, StorageFormat::parse(name)).ae});
  return out;
}

LjConfig table_config(LjBuffer b, double ratio, long long samples, LjSampling sampling) {
  LjConfig c;
  c.buffer = b;
  c.near = 1;
  c.far = ratio;
  c.samples = samples;
  c.sampling = sampling;
  return c;
}

std::string split_key(const char* sampling, int bits, LjBuffer b, double r) {
  return fmt::format("{}/{}/{}/{:.17g}", sampling, bits, to_string(b), r);
}
std::string picks_key(double r) {
  return fmt::format("32bit/{:.17g}", r);
}

}  // namespace depthprec
