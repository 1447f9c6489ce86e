// Host face of formats/depth_format.h: parsing of format names, the -D defines that specialise a
// kernel for one format, and the binary64 queries (floor code, spacing) the metrics need.
#pragma once

#include <cstdint>
#include <string>

#include "formats/depth_format.h"

namespace depthprec {

enum class Rounding { nearest_even, truncate };
enum class Denormals { keep, flush };
// How the pipeline computes a unorm code (formats/depth_format.h DF_CONVERT_*).
enum class Conversion { exact, llvmpipe, softpipe };

const char* to_string(Rounding r);
const char* to_string(Denormals d);
Rounding parse_rounding(const std::string& s);    // throws InputError
Denormals parse_denormals(const std::string& s);  // throws InputError
const char* to_string(Conversion c);
Conversion parse_conversion(const std::string& s);  // throws InputError

class StorageFormat {
 public:
  // "unorm24", "float32", "e4m12", ... Throws InputError saying what is allowed.
  // conversion llvmpipe: only unorm16, unorm24 and unorm32 have one (InputError otherwise); it
  // does not apply to float formats.
  static StorageFormat parse(const std::string& name, Rounding rounding = Rounding::nearest_even,
                             Denormals denormals = Denormals::keep,
                             Conversion conversion = Conversion::exact);

  const std::string& name() const { return name_; }
  const df_format& spec() const { return spec_; }
  Rounding rounding() const { return rounding_; }
  Denormals denormals() const { return denormals_; }
  bool is_unorm() const { return spec_.kind == DF_KIND_UNORM; }
  unsigned bits() const { return spec_.bits; }
  uint32_t max_code() const { return spec_.max_code; }

  uint32_t encode(float d) const { return df_encode(d, spec_); }
  uint32_t encode64(double d) const {
    return df_encode_f64(d, spec_);
  }  // correctly rounded from binary64
  double decode(uint32_t code) const { return df_decode(code, spec_); }
  uint32_t code_above(uint32_t c) const { return df_code_above(c, spec_); }
  uint32_t code_below(uint32_t c) const { return df_code_below(c); }

  // Largest code whose value is <= v, for any binary64 v (exact, no rounding of v first).
  uint32_t code_floor(double v) const;
  // Spacing between the code at or below v and the next code above it (for the largest code,
  // the spacing below it).
  double spacing_at(double v) const;
  double smallest_positive() const { return decode(1); }
  double largest() const { return decode(spec_.max_code); }

  // -D defines that make DF_FORMAT_FROM_DEFINES() this format inside a kernel.
  std::string defines() const;

 private:
  std::string name_;
  df_format spec_{};
  Rounding rounding_ = Rounding::nearest_even;
  Denormals denormals_ = Denormals::keep;
};

}  // namespace depthprec
