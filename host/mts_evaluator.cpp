#include "host/mts_evaluator.h"

#include <algorithm>
#include <chrono>

namespace depthprec {

namespace {

constexpr int kTriStride = 32;
constexpr int kProbeStride = 24;
constexpr uint32_t kFight = 1, kClipped = 2, kNonFinite = 4, kUncovered = 8, kBounds = 16;
constexpr int kCountShift = 8;
constexpr uint32_t kVertexNonFinite = 1;  // kernels/mts.cl V_NONFINITE

// Kernel rows per band that mts_frame_bounds decides at once from code bounds: a band's depth
// range grows with its height, so smaller bands are decided closer to the MTS but cost more
// bounds work per row.
constexpr cl_uint kBandRows = 32;

// Fixed work-group sizes: PoCL compiles a kernel once per local size, so letting it choose per
// launch (a new size for every batch shape) recompiles again and again.
constexpr size_t kLocal = 16;
cl::NDRange padded(size_t n) { return cl::NDRange((n + kLocal - 1) / kLocal * kLocal); }

int triangles(const Scene& s) { return 2 * s.plane_subdivisions * s.plane_subdivisions; }

// Floats per plane in the set-up buffer (kernels/mts.cl PLANE_STRIDE): triangle records, then
// six arrays of the 3*NT edges padded to a multiple of 16, then each quad row's y-range.
size_t plane_floats(const Scene& s) {
  const size_t edges = (3 * triangles(s) + 15) / 16 * 16;
  return static_cast<size_t>(triangles(s)) * kTriStride + 6 * edges + 2 * s.plane_subdivisions;
}

}  // namespace

int batch_frames(int done, int total) {
  const int want = done == 0 ? 4 : done < 20 ? 16 : 64;
  return std::min(want, total - done);
}

std::vector<size_t> undecided(const std::vector<bool>& decided) {
  std::vector<size_t> out;
  for (size_t i = 0; i < decided.size(); ++i)
    if (!decided[i]) out.push_back(i);
  return out;
}

std::vector<uint64_t> fold_launch(const std::vector<uint32_t>& rows, const std::vector<size_t>& active,
                                  int first_frame, int frames, size_t kernel_h, std::vector<ProbeResult>& results,
                                  std::vector<bool>& decided, uint64_t& after_decision) {
  std::vector<uint64_t> probe_pairs(active.size(), 0);
  for (size_t i = 0; i < active.size(); ++i) {
    ProbeResult& r = results[active[i]];
    for (int f = 0; f < frames; ++f) {
      uint32_t flags = 0;
      uint64_t frame_pairs = 0;
      for (size_t y = 0; y < kernel_h; ++y) {
        const uint32_t v = rows[(i * frames + f) * kernel_h + y];
        flags |= v;
        frame_pairs += v >> kCountShift;
      }
      probe_pairs[i] += frame_pairs;
      if (decided[active[i]]) {  // frames after the deciding one: work, not outcome
        after_decision += frame_pairs;
        continue;
      }
      r.frames = first_frame + f + 1;
      r.any_clipped |= (flags & kClipped) != 0;
      r.any_uncovered |= (flags & kUncovered) != 0;
      if (flags & kNonFinite) {
        r.any_non_finite = true;
        r.outcome = Outcome::non_finite;
        decided[active[i]] = true;
      } else if (flags & kFight) {
        r.outcome = Outcome::fight;
        decided[active[i]] = true;
      }
    }
    r.fragment_pairs += probe_pairs[i];
  }
  return probe_pairs;
}

void finish_outcomes(std::vector<ProbeResult>& results, const std::vector<bool>& decided) {
  for (size_t i = 0; i < results.size(); ++i)
    if (!decided[i] && results[i].any_clipped) results[i].outcome = Outcome::clipped;
}

const char* to_string(Outcome o) {
  switch (o) {
    case Outcome::clean: return "clean";
    case Outcome::fight: return "fight";
    case Outcome::clipped: return "clipped";
    case Outcome::non_finite: return "non_finite";
  }
  return "?";
}

MtsEvaluator::MtsEvaluator(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair, bool code_bounds)
    : rt_(rt), scene_(scene), pair_(pair), variant_(mts_variant(scene, pair)), code_bounds_(code_bounds) {
  const cl::Program program = rt_.program(variant_.program, variant_.options);
  setup_ = cl::Kernel(program, "mts_setup");
  raster_ = cl::Kernel(program, "mts_raster");
  bounds_ = cl::Kernel(program, "mts_frame_bounds");
  codes_ = cl::Kernel(program, "mts_codes");
}

cl::Event MtsEvaluator::setup(const std::vector<Probe>& probes, const std::vector<size_t>& active,
                              int first_frame, int frames, cl::Buffer& probe_buf, cl::Buffer& tris,
                              cl::Buffer& vflags) {
  const size_t n = active.size();
  std::vector<float> consts(n * kProbeStride);
  std::vector<float> mats(n * frames * 2 * 16);
  for (size_t i = 0; i < n; ++i) {
    const Probe& p = probes[active[i]];
    const ProbeConstants pc = probe_constants(scene_, pair_, p.z);
    const auto packed = pc.packed();
    std::copy(packed.begin(), packed.end(), consts.begin() + i * kProbeStride);
    for (int f = 0; f < frames; ++f) {
      const Mat4f a = plane_matrix(scene_, pc, p.z, first_frame + f);
      const Mat4f b = plane_matrix(scene_, pc, p.z + p.s, first_frame + f);
      float* dst = mats.data() + ((i * frames + f) * 2) * 16;
      std::copy(a.begin(), a.end(), dst);
      std::copy(b.begin(), b.end(), dst + 16);
    }
  }
  probe_buf = cl::Buffer(rt_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                         sizeof(float) * consts.size(), consts.data());
  cl::Buffer mat_buf(rt_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                     sizeof(float) * mats.size(), mats.data());
  const size_t planes = n * frames * 2;
  tris = cl::Buffer(rt_.context(), CL_MEM_READ_WRITE, sizeof(float) * planes * plane_floats(scene_));
  vflags = cl::Buffer(rt_.context(), CL_MEM_READ_WRITE, sizeof(uint32_t) * planes);
  setup_.setArg(0, probe_buf);
  setup_.setArg(1, mat_buf);
  setup_.setArg(2, static_cast<cl_uint>(frames));
  setup_.setArg(3, 0.5f * static_cast<float>(scene_.viewport_w));
  setup_.setArg(4, 0.5f * static_cast<float>(scene_.viewport_h));
  setup_.setArg(5, origin_x());
  setup_.setArg(6, origin_y());
  setup_.setArg(7, static_cast<cl_uint>(scene_.kernel_w));
  setup_.setArg(8, static_cast<cl_uint>(scene_.kernel_h));
  setup_.setArg(9, tris);
  setup_.setArg(10, vflags);
  setup_.setArg(11, static_cast<cl_uint>(planes));
  cl::Event done;
  rt_.queue().enqueueNDRangeKernel(setup_, cl::NullRange, padded(planes), cl::NDRange(kLocal),
                                   nullptr, &done);
  ++launches_;
  return done;
}

namespace {
double device_seconds(const cl::Event& e) {
  return 1e-9 * static_cast<double>(e.getProfilingInfo<CL_PROFILING_COMMAND_END>() -
                                    e.getProfilingInfo<CL_PROFILING_COMMAND_START>());
}
}  // namespace

std::vector<ProbeResult> MtsEvaluator::run(const std::vector<Probe>& probes) {
  std::vector<ProbeResult> results(probes.size());
  std::vector<bool> decided(probes.size(), false);
  const auto kw = static_cast<cl_uint>(scene_.kernel_w), kh = static_cast<cl_uint>(scene_.kernel_h);
  const float ox = origin_x(), oy = origin_y();
  const cl_uint bands = (kh + kBandRows - 1) / kBandRows;
  int done = 0;
  while (done < scene_.frames) {
    const std::vector<size_t> active = undecided(decided);
    if (active.empty()) break;
    const int frames = batch_frames(done, scene_.frames);
    const auto t0 = std::chrono::steady_clock::now();
    cl::Buffer probe_buf, tris, vflags;
    const cl::Event setup_done = setup(probes, active, done, frames, probe_buf, tris, vflags);
    const size_t items = active.size() * frames * kh;
    const size_t band_items = active.size() * frames * bands;
    cl::Buffer decided_bands(rt_.context(), CL_MEM_READ_WRITE, sizeof(uint32_t) * band_items);
    // the arguments mts_frame_bounds and mts_raster share, in the same order
    auto set_frame_args = [&](cl::Kernel& k) {
      k.setArg(0, probe_buf);
      k.setArg(1, tris);
      k.setArg(2, vflags);
      k.setArg(3, kw);
      k.setArg(4, kh);
      k.setArg(5, ox);
      k.setArg(6, oy);
      k.setArg(7, static_cast<cl_uint>(frames));
    };
    cl::Event bounds_done;
    if (code_bounds_) {
      set_frame_args(bounds_);
      bounds_.setArg(8, bands);
      bounds_.setArg(9, kBandRows);
      bounds_.setArg(10, decided_bands);
      bounds_.setArg(11, static_cast<cl_uint>(band_items));
      rt_.queue().enqueueNDRangeKernel(bounds_, cl::NullRange, padded(band_items), cl::NDRange(kLocal),
                                       nullptr, &bounds_done);
      ++launches_;
    } else {
      rt_.queue().enqueueFillBuffer(decided_bands, cl_uint{0}, 0, sizeof(uint32_t) * band_items, nullptr,
                                    &bounds_done);
    }
    std::vector<uint32_t> rows(items);
    cl::Buffer result(rt_.context(), CL_MEM_WRITE_ONLY, sizeof(uint32_t) * items);
    set_frame_args(raster_);
    raster_.setArg(8, decided_bands);
    raster_.setArg(9, bands);
    raster_.setArg(10, kBandRows);
    raster_.setArg(11, result);
    raster_.setArg(12, static_cast<cl_uint>(items));
    cl::Event raster_done;
    rt_.queue().enqueueNDRangeKernel(raster_, cl::NullRange, padded(items), cl::NDRange(kLocal),
                                     nullptr, &raster_done);
    rt_.queue().enqueueReadBuffer(result, CL_TRUE, 0, sizeof(uint32_t) * items, rows.data());
    for (const uint32_t v : rows)
      if (v & kBounds) by_bounds_ += v >> kCountShift;
    ++launches_;
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double ksecs = device_seconds(setup_done) + device_seconds(bounds_done) + device_seconds(raster_done);
    wall_seconds_ += secs;
    kernel_seconds_ += ksecs;

    const std::vector<uint64_t> probe_pairs =
        fold_launch(rows, active, done, frames, kh, results, decided, after_decision_);
    uint64_t launch_pairs = 0;
    for (const uint64_t n : probe_pairs) launch_pairs += n;
    for (size_t i = 0; i < active.size(); ++i) {
      const double share = launch_pairs ? static_cast<double>(probe_pairs[i]) / static_cast<double>(launch_pairs)
                                        : 1.0 / static_cast<double>(active.size());
      results[active[i]].seconds += secs * share;
      results[active[i]].kernel_seconds += ksecs * share;
      results[active[i]].launches += code_bounds_ ? 3 : 2;  // set-up, bounds and raster
    }
    pairs_ += launch_pairs;
    done += frames;
  }
  finish_outcomes(results, decided);
  for (const auto& r : results) by_outcome_[static_cast<size_t>(r.outcome)] += r.fragment_pairs;
  return results;
}

FrameCodes MtsEvaluator::codes(const Probe& probe, int frame) {
  cl::Buffer probe_buf, tris, vflags;
  setup({probe}, {0}, frame, 1, probe_buf, tris, vflags);
  const auto kw = static_cast<cl_uint>(scene_.kernel_w), kh = static_cast<cl_uint>(scene_.kernel_h);
  const size_t pixels = static_cast<size_t>(kw) * kh;
  cl::Buffer out(rt_.context(), CL_MEM_WRITE_ONLY, sizeof(uint32_t) * 4 * pixels);
  codes_.setArg(0, probe_buf);
  codes_.setArg(1, tris);
  codes_.setArg(2, kw);
  codes_.setArg(3, origin_x());
  codes_.setArg(4, origin_y());
  codes_.setArg(5, out);
  codes_.setArg(6, kh);
  rt_.queue().enqueueNDRangeKernel(codes_, cl::NullRange, padded(kh), cl::NDRange(kLocal));
  std::vector<uint32_t> raw(4 * pixels);
  rt_.queue().enqueueReadBuffer(out, CL_TRUE, 0, sizeof(uint32_t) * raw.size(), raw.data());
  uint32_t vf[2] = {0, 0};
  rt_.queue().enqueueReadBuffer(vflags, CL_TRUE, 0, sizeof vf, vf);
  FrameCodes fc;
  fc.width = static_cast<int>(kw);
  fc.height = static_cast<int>(kh);
  for (size_t i = 0; i < pixels; ++i) {
    fc.code_a.push_back(raw[4 * i]);
    fc.code_b.push_back(raw[4 * i + 1]);
    fc.status_a.push_back((vf[0] & kVertexNonFinite) ? 2 : static_cast<uint8_t>(raw[4 * i + 2]));
    fc.status_b.push_back((vf[1] & kVertexNonFinite) ? 2 : static_cast<uint8_t>(raw[4 * i + 3]));
  }
  return fc;
}

}  // namespace depthprec
