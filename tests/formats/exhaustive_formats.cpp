// Exhaustive proof of one storage format's encoder: every binary32 value in [0, 1] (bit patterns
// 0 .. 0x3f800000, 1,065,353,217 inputs), both rounding modes, the OpenCL kernel's code against
// the independent reference (format_reference.cpp) and against the host build of the same
// formats/ source. Usage: exhaustive_formats FORMAT
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <thread>
#include <vector>

#include "host/model/storage_format.h"
#include "host/runtime/device_encode.h"
#include "host/runtime/opencl_runtime.h"
#include "tests/formats/format_reference.h"

using namespace depthprec;

namespace {

constexpr uint32_t kLast = 0x3f800000u;  // 1.0f
constexpr uint32_t kChunk = 1u << 24;

struct Tally {
  std::atomic<uint64_t> checked{0}, vs_reference{0}, vs_host{0}, vector_path{0};
  std::atomic<uint32_t> first_bad{0xffffffffu};
};

void check_span(const std::vector<uint32_t>& codes, uint32_t first, uint32_t begin, uint32_t end,
                const StorageFormat& f, const test::ReferenceFormat& rf, bool truncate, Tally& t) {
  uint64_t bad_ref = 0, bad_host = 0;
  const auto as_float = [](uint32_t bits) {
    float d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  };
  test::ReferenceWalk reference(rf, truncate, f.denormals() == Denormals::flush,
                                as_float(first + begin));
  // A block at a time: the reference's codes (unorm up to 29 bits in its vectorized loop), the
  // host build's, then one pass counting both kinds of mismatch; a block with any is walked again
  // to report them.
  const df_format spec = f.spec();
  constexpr uint32_t kBlock = 4096;
  std::vector<uint32_t> ref(kBlock), host(kBlock);
  for (uint32_t b = begin; b < end; b += kBlock) {
    const uint32_t n = std::min(kBlock, end - b);
    if (rf.unorm && rf.bits <= 29)
      test::reference_unorm_codes(first + b, n, rf.bits, truncate, ref.data());
    else
      for (uint32_t k = 0; k < n; ++k) ref[k] = reference.next(as_float(first + b + k));
    for (uint32_t k = 0; k < n; ++k) host[k] = df_encode(as_float(first + b + k), spec);
    const uint32_t* dev = codes.data() + b;
    uint32_t block_ref = 0, block_host = 0;
    for (uint32_t k = 0; k < n; ++k) {
      block_ref += dev[k] != ref[k];
      block_host += dev[k] != host[k];
    }
    bad_host += block_host;
    if (block_ref == 0) continue;
    for (uint32_t k = 0; k < n; ++k) {
      if (dev[k] == ref[k]) continue;
      const uint32_t bits = first + b + k;
      if (++bad_ref <= 3)
        fmt::print(stderr, "  mismatch: d = {:a} ({:#010x}): device {} reference {}\n",
                   as_float(bits), bits, dev[k], ref[k]);
      uint32_t prev = t.first_bad.load();
      while (bits < prev && !t.first_bad.compare_exchange_weak(prev, bits)) {
      }
    }
  }
  t.checked += end - begin;
  t.vs_reference += bad_ref;
  t.vs_host += bad_host;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    fmt::print(stderr, "usage: exhaustive_formats FORMAT\n");
    return 2;
  }
  const std::string name = argv[1];
  OpenClRuntime rt;
  const auto rf = test::reference_format(name);
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  bool ok = true;
  for (const Rounding rounding : {Rounding::nearest_even, Rounding::truncate}) {
    const auto f = StorageFormat::parse(name, rounding);
    const bool truncate = rounding == Rounding::truncate;
    Tally tally;
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<uint32_t> codes;
    for (uint64_t first = 0; first <= kLast; first += kChunk) {
      const auto count = static_cast<uint32_t>(std::min<uint64_t>(kChunk, kLast + 1 - first));
      tally.vector_path += device_encode_range(rt, f, static_cast<uint32_t>(first), count, codes);
      std::vector<std::thread> pool;
      for (unsigned k = 0; k < threads; ++k) {
        const uint32_t b = static_cast<uint32_t>(uint64_t{count} * k / threads);
        const uint32_t e = static_cast<uint32_t>(uint64_t{count} * (k + 1) / threads);
        pool.emplace_back(check_span, std::cref(codes), static_cast<uint32_t>(first), b, e,
                          std::cref(f), std::cref(rf), truncate, std::ref(tally));
      }
      for (auto& th : pool) th.join();
    }
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    fmt::print(
        "exhaustive {} {}: {} inputs checked on {}, {} mismatches vs reference, {} vs host "
        "build, {} in the 16-lane path ({:.1f} s)\n",
        name, to_string(rounding), tally.checked.load(), rt.info().device_name,
        tally.vs_reference.load(), tally.vs_host.load(), tally.vector_path.load(), secs);
    if (tally.checked.load() != uint64_t{kLast} + 1 || tally.vs_reference.load() != 0 ||
        tally.vs_host.load() != 0 || tally.vector_path.load() != 0)
      ok = false;
  }
  fmt::print("{}\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
