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

std::vector<BatchUnit> lj_table_units(OpenClRuntime& rt, long long samples) {
  std::vector<BatchUnit> units;
  auto aes = [](const std::vector<double>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (double x : v) a.push_back(json_number(x));
    return nlohmann::json{{"ae", a}};
  };
  for (const char* sampling : kLjSamplings)
    for (int bits : kLjBits)
      for (const LjBuffer b : kLjBuffers)
        for (double r : kLjRatios)
          units.push_back(
              {split_key(sampling, bits, b, r), [&rt, samples, sampling, bits, b, r, aes] {
                 std::vector<double> v;
                 for (const auto& x :
                      sweep(rt, table_config(b, r, samples, parse_lj_sampling(sampling)), bits))
                   v.push_back(x.ae);
                 return aes(v);
               }});
  for (double r : kLjRatios)
    units.push_back({picks_key(r), [&rt, samples, r, aes] {
                       std::vector<double> v;
                       for (const auto& p : kLjPicks)
                         v.push_back(lj_average_error_device(
                                         rt,
                                         table_config(p.buffer, r, samples, LjSampling::uniform),
                                         StorageFormat::parse(p.format))
                                         .ae);
                       return aes(v);
                     }});
  return units;
}

}  // namespace depthprec
