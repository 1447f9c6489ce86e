// The Lapidous-Jiao experiments: the formats of a buffer's bits, a sweep of them, and the
// paper's tables (lj-table): their f/d ratios, samplings, bit counts, buffers, its 32-bit picks,
// each row of which `lj-table` runs as one batch unit (host/cli/cmd_lj.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/lj/lj_metric.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

// The formats of a `bits`-bit buffer: E = 0 (integer) .. min(8, bits - 1).
std::vector<std::string> split_formats(int bits);

struct Ranked {
  std::string format;
  int e = 0;
  double ae = 0;
};
// ae of every format of split_formats(bits) for the configuration, on the device.
std::vector<Ranked> sweep(OpenClRuntime& rt, const LjConfig& c, int bits);

// lj-table's experiments.
inline const std::vector<double> kLjRatios = {2, 5, 10, 20, 50, 100, 200, 500, 1000, 1e4, 1e6};
inline const char* const kLjSamplings[] = {"uniform", "increasing"};
inline const int kLjBits[] = {16, 24};
inline const LjBuffer kLjBuffers[] = {LjBuffer::z, LjBuffer::w, LjBuffer::inverse_w,
                                      LjBuffer::complementary_z};
// LJ99 fig. 11: 32-bit buffers.
struct LjPick {
  LjBuffer buffer;
  const char* format;
};
inline const LjPick kLjPicks[] = {{LjBuffer::z, "float32"},
                                  {LjBuffer::z, "unorm24"},
                                  {LjBuffer::z, "unorm32"},
                                  {LjBuffer::w, "unorm32"},
                                  {LjBuffer::inverse_w, "float32"},
                                  {LjBuffer::complementary_z, "float32"},
                                  {LjBuffer::complementary_z, "e4m24"}};

LjConfig table_config(LjBuffer b, double ratio, long long samples, LjSampling sampling);
// The records' keys: a split-format row, and a row of the 32-bit picks.
std::string split_key(const char* sampling, int bits, LjBuffer b, double r);
std::string picks_key(double r);

}  // namespace depthprec
