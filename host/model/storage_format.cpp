#include "host/model/storage_format.h"

#include <fmt/format.h>

#include <cmath>
#include <regex>

#include "host/base/did_you_mean.h"
#include "host/base/errors.h"
#include "host/base/named_choice.h"

namespace depthprec {

namespace {

const char* kAllowedFormats =
    "unorm<b> (b = 1..32), float16, float24, float32, or e<E>m<M> (Lapidous-Jiao: no sign, "
    "bias 2^E; E = 1..8, M = 0..31, E + M <= 32)";

}  // namespace

const char* to_string(Rounding r) {
  return r == Rounding::nearest_even ? "nearest_even" : "truncate";
}
const char* to_string(Denormals d) {
  return d == Denormals::keep ? "keep" : "flush";
}

Rounding parse_rounding(const std::string& s) {
  return named_choice<Rounding>(
      "rounding", s, {{"nearest_even", Rounding::nearest_even}, {"truncate", Rounding::truncate}});
}

Denormals parse_denormals(const std::string& s) {
  return named_choice<Denormals>("denormals mode", s,
                                 {{"keep", Denormals::keep}, {"flush", Denormals::flush}});
}

const char* to_string(Conversion c) {
  return c == Conversion::exact ? "exact" : c == Conversion::llvmpipe ? "llvmpipe" : "softpipe";
}

Conversion parse_conversion(const std::string& s) {
  return named_choice<Conversion>("conversion", s,
                                  {{"exact", Conversion::exact},
                                   {"llvmpipe", Conversion::llvmpipe},
                                   {"softpipe", Conversion::softpipe}});
}

StorageFormat StorageFormat::parse(const std::string& name, Rounding rounding, Denormals denormals,
                                   Conversion conversion) {
  const df_u32 r = rounding == Rounding::nearest_even ? DF_ROUND_NEAREST_EVEN : DF_ROUND_TRUNCATE;
  const df_u32 fl = denormals == Denormals::flush ? 1u : 0u;
  StorageFormat f;
  f.name_ = name;
  f.rounding_ = rounding;
  f.denormals_ = denormals;
  std::smatch m;
  if (std::regex_match(name, m, std::regex("unorm([0-9]+)"))) {
    const long b = m[1].length() > 3 ? 999 : std::stol(m[1]);
    if (b < 1 || b > 32)
      throw InputError(
          fmt::format("storage format '{}': unorm takes 1 to 32 bits, not {}", name, m[1].str()));
    f.spec_ = df_make_unorm(static_cast<df_u32>(b), r, fl);
    if (conversion != Conversion::exact) {
      const char* driver = to_string(conversion);
      if (b != 16 && b != 24 && b != 32)
        throw InputError(fmt::format(
            "storage format '{}': pipeline.conversion {} exists for unorm16, unorm24 and "
            "unorm32 only (the depth formats {} stores)",
            name, driver, driver));
      if (rounding != Rounding::nearest_even)
        throw InputError(
            fmt::format("storage format '{}': pipeline.conversion {} rounds as {} does; "
                        "pipeline.rounding must stay nearest_even",
                        name, driver, driver));
      f.spec_ = df_with_convert(
          f.spec_, conversion == Conversion::llvmpipe ? DF_CONVERT_LLVMPIPE : DF_CONVERT_SOFTPIPE);
    }
  } else if (name == "float32") {
    f.spec_ = df_make_float(8, 23, 1, r, fl);
  } else if (name == "float24") {
    f.spec_ = df_make_float(8, 15, 1, r, fl);
  } else if (name == "float16") {
    f.spec_ = df_make_float(5, 10, 1, r, fl);
  } else if (std::regex_match(name, m, std::regex("e([0-9]+)m([0-9]+)"))) {
    const long e = m[1].length() > 3 ? 999 : std::stol(m[1]);
    const long mm = m[2].length() > 3 ? 999 : std::stol(m[2]);
    if (e == 0)
      throw InputError(fmt::format(
          "storage format '{}': E = 0 leaves no exponent; the integer format with {} bits is "
          "unorm{}",
          name, mm, mm));
    if (e > 8)
      throw InputError(fmt::format(
          "storage format '{}': E = {} is too wide; E = 1..8 (with bias 2^8 every positive "
          "binary32 depth is already a normal number)",
          name, e));
    if (mm > 31 || e + mm > 32)
      throw InputError(fmt::format("storage format '{}': {} bits in all; M = 0..31 and E + M <= 32",
                                   name, e + mm));
    f.spec_ = df_make_float(static_cast<df_i32>(e), static_cast<df_i32>(mm), 0, r, fl);
  } else {
    throw InputError(fmt::format("unknown storage format '{}'{}: expected {}", name,
                                 format_suggestion(name), kAllowedFormats));
  }
  return f;
}

uint32_t StorageFormat::code_floor(double v) const {
  if (!(v > 0.0)) return 0;  // also NaN
  if (v >= largest()) return spec_.max_code;
  if (spec_.kind == DF_KIND_UNORM) {
    // floor(v * (2^b - 1)) exactly: v = mant * 2^e with a 53-bit integer mant; below 2^-40 the
    // product is < 2^-8 for every b <= 32.
    if (v < 0x1p-40) return 0;
    int e = 0;
    const double fr = std::frexp(v, &e);  // v = fr * 2^e, fr in [0.5, 1)
    const auto mant = static_cast<unsigned __int128>(std::ldexp(fr, 53));
    const int shift = 53 - e;  // v = mant * 2^-shift, shift in 53..93
    const unsigned __int128 prod = mant * spec_.max_code;
    return static_cast<uint32_t>(prod >> shift);
  }
  // float formats: floor(v / quantum) with a power-of-two quantum is exact in binary64
  int e = 0;
  std::frexp(v, &e);
  const int p = e - 1;  // 2^p <= v < 2^(p+1)
  const int qp = std::max(p, 1 - spec_.bias);
  const double n = std::floor(std::ldexp(v, spec_.man_bits - qp));
  const uint64_t code =
      (static_cast<uint64_t>(qp + spec_.bias - 1) << spec_.man_bits) + static_cast<uint64_t>(n);
  return static_cast<uint32_t>(std::min<uint64_t>(code, spec_.max_code));
}

double StorageFormat::spacing_at(double v) const {
  return df_spacing_at(v, spec_);
}

std::string StorageFormat::defines() const {
  if (spec_.kind == DF_KIND_UNORM)
    return fmt::format(
        "-DDF_KIND=0 -DDF_BITS={}u -DDF_ROUNDING={}u -DDF_FLUSH={}u -DDF_CONVERT={}u", spec_.bits,
        spec_.rounding, spec_.flush, spec_.convert);
  const bool ieee = spec_.bias == (1 << (spec_.exp_bits - 1)) - 1;
  return fmt::format(
      "-DDF_KIND=1 -DDF_E={} -DDF_M={} -DDF_IEEE={}u -DDF_ROUNDING={}u -DDF_FLUSH={}u",
      spec_.exp_bits, spec_.man_bits, ieee ? 1 : 0, spec_.rounding, spec_.flush);
}

}  // namespace depthprec
