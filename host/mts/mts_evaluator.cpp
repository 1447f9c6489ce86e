#include "host/mts/mts_evaluator.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "host/base/errors.h"
#include "host/mts/mts_evaluator_parts.h"
#include "host/runtime/kernel_args.h"
#include "interface/mts_layout.h"

namespace depthprec {

using namespace mts_parts;

MtsEvaluator::MtsEvaluator(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                           const Orientations& orientations, bool shortcuts, Kernels kernels)
    : rt_(rt),
      scene_(scene),
      pair_(pair),
      orientations_(orientations),
      variant_(mts_variant(scene, pair)),
      shortcuts_(shortcuts),
      fill_a_codes_(variant_.cache_a_codes && !orientations.chunk) {
  program_ = rt_.program(variant_.program, variant_.options);
  // The test kernels come from a program of their own; every other kernel from the production one,
  // so a test shares the kernels PoCL compiled for a run of the same variant, and the reverse.
  if (kernels == Kernels::with_tests)
    test_program_ = rt_.program("kernels/mts_test.cl", variant_.options);
  setup_ = cl::Kernel(rt_.program(variant_.setup_program, variant_.setup_options), "mts_setup");
  a_rows_ = cl::Kernel(program_, "mts_a_rows");
  a_bands_ = cl::Kernel(program_, "mts_a_bands");
  raster_ = cl::Kernel(program_, "mts_raster");
  bounds_ = cl::Kernel(program_, "mts_frame_bounds");
  plane_floats_ = plane_record_floats(scene);
  row_words_ = MTS_ROW_WORDS;
  band_words_ = MTS_BAND_WORDS;
  decided_words_ = MTS_DECIDED_WORDS;
  share_plane_a_budget(1);
}

void MtsEvaluator::share_plane_a_budget(int evaluators) {
  max_slots_ = plane_a_slots(scene_, variant_.cache_a_codes, evaluators);
}

size_t MtsEvaluator::reserve_plane_a(const std::vector<Probe>& probes) {
  std::vector<double> zs;
  for (const Probe& p : probes) zs.push_back(p.z);
  std::sort(zs.begin(), zs.end());
  const size_t distinct = static_cast<size_t>(std::unique(zs.begin(), zs.end()) - zs.begin());
  const size_t want = std::min(max_slots_, distinct);
  if (want <= a_.capacity) return distinct;
  a_ = PlaneACache{};  // buffers are allocated at the next fill; what the old ones held is refilled
  a_.capacity = want;
  a_.z.assign(want, std::numeric_limits<double>::quiet_NaN());
  a_.last_use.assign(want, 0);
  return distinct;
}

cl_uint MtsEvaluator::bands() const {
  return band_count(scene_);
}

MtsKernelArea MtsEvaluator::area() const {
  return MtsKernelArea{static_cast<cl_uint>(scene_.kernel_w),
                       static_cast<cl_uint>(scene_.kernel_h),
                       origin_x(),
                       origin_y(),
                       bands(),
                       kBandRows};
}

cl::Event MtsEvaluator::setup(const cl::Buffer& consts, const std::vector<float>& mats,
                              cl_uint per_probe, cl_uint first_plane, cl::Buffer& tris,
                              cl::Buffer& vflags) {
  const size_t planes = mats.size() / plane_words(scene_);
  const cl::Buffer mat_buf = buffer_of(rt_.context(), mats);
  MtsSetupBuffers b;
  b.probes = &consts;
  b.mats = &mat_buf;
  b.tris = &tris;
  b.vflags = &vflags;
  MtsSetupArgs args{};
  args.area = area();
  args.half_w = 0.5f * static_cast<float>(scene_.viewport_w);
  args.half_h = 0.5f * static_cast<float>(scene_.viewport_h);
  args.per_probe = per_probe;
  args.first_plane = first_plane;
  args.count = static_cast<cl_uint>(planes);
  bind(setup_, b, args);
  cl::Event done;
  launch(setup_, primed_.setup, padded(planes), cl::NDRange(kLocal), &done);
  return done;
}

cl::Buffer MtsEvaluator::reuse_or_make(cl::Buffer& spare, size_t bytes) {
  // A larger buffer serves too (the kernels index the cache by its slots, never by its size),
  // but not a much larger one: the pages the last evaluator touched stay resident.
  if (spare() != nullptr) {
    const size_t have = spare.getInfo<CL_MEM_SIZE>();
    if (have >= bytes && have <= bytes + bytes / 2) return std::move(spare);
  }
  return cl::Buffer(rt_.context(), CL_MEM_READ_WRITE, bytes);
}

size_t MtsEvaluator::PlaneABuffers::bytes() const {
  size_t out = 0;
  for (const cl::Buffer* b : {&consts, &tris, &vflags, &rows, &bands, &codes, &ref_tris, &ref_rows})
    if ((*b)() != nullptr) out += b->getInfo<CL_MEM_SIZE>();
  return out;
}

MtsEvaluator::PlaneABuffers MtsEvaluator::release_plane_a_buffers() {
  rt_.queue().finish();                 // no launch of this evaluator still reads or writes them
  if (a_.tris() == nullptr) return {};  // never filled
  PlaneABuffers out{std::move(a_.consts),   std::move(a_.tris),    std::move(a_.vflags),
                    std::move(a_.rows),     std::move(a_.bands),   std::move(a_.codes),
                    std::move(a_.ref_tris), std::move(a_.ref_rows)};
  // the moved-from buffers are null, so a later run fills the cache anew: no slot is held
  std::fill(a_.z.begin(), a_.z.end(), NAN);
  a_.has_ref = false;
  return out;
}

std::vector<cl_uint> MtsEvaluator::cache_plane_a(const std::vector<Probe>& probes,
                                                 const std::vector<size_t>& active,
                                                 double& kernel_seconds,
                                                 std::vector<int>& launches) {
  const auto kh = static_cast<cl_uint>(scene_.kernel_h);
  const auto frames = static_cast<cl_uint>(scene_.frames);
  if (a_.tris() == nullptr) {
    const std::array<size_t, 8> b =
        plane_a_buffer_bytes(scene_, variant_.cache_a_codes, a_.capacity);
    a_.consts = reuse_or_make(spare_.consts, b[0]);
    a_.tris = reuse_or_make(spare_.tris, b[1]);
    a_.vflags = reuse_or_make(spare_.vflags, b[2]);
    a_.rows = reuse_or_make(spare_.rows, b[3]);
    a_.bands = reuse_or_make(spare_.bands, b[4]);
    a_.codes = reuse_or_make(spare_.codes, std::max<size_t>(b[5], 1));  // never empty
    a_.ref_tris = reuse_or_make(spare_.ref_tris, b[6]);
    a_.ref_rows = reuse_or_make(spare_.ref_rows, b[7]);
    spare_ = {};
    a_.has_ref = false;
  }
  ++a_.clock;
  constexpr cl_uint kNotHeld = std::numeric_limits<cl_uint>::max();
  std::vector<cl_uint> slots(active.size(), kNotHeld);
  launches.assign(active.size(), 0);
  std::vector<bool> in_use(a_.capacity, false);
  for (size_t i = 0; i < active.size(); ++i) {  // first the slots already held, so none is evicted
    const auto it = std::find(a_.z.begin(), a_.z.end(), probes[active[i]].z);
    if (it == a_.z.end()) continue;
    slots[i] = static_cast<cl_uint>(it - a_.z.begin());
    in_use[slots[i]] = true;
    a_.last_use[slots[i]] = a_.clock;
  }
  for (size_t i = 0; i < active.size(); ++i) {
    if (slots[i] != kNotHeld) continue;
    const double z = probes[active[i]].z;
    // a distance filled earlier in this loop (several probes of one distance)
    const auto it = std::find(a_.z.begin(), a_.z.end(), z);
    if (it != a_.z.end()) {
      slots[i] = static_cast<cl_uint>(it - a_.z.begin());
      continue;
    }
    // the least recently used slot no probe of this launch needs (run() keeps the distances of
    // one launch within the capacity)
    size_t slot = a_.capacity;
    for (size_t k = 0; k < a_.capacity; ++k)
      if (!in_use[k] && (slot == a_.capacity || a_.last_use[k] < a_.last_use[slot])) slot = k;
    if (slot == a_.capacity)
      throw Error(ExitCode::internal, "plane-A cache: more distances in one launch than slots");
    a_.z[slot] = z;
    a_.last_use[slot] = a_.clock;
    in_use[slot] = true;
    slots[i] = static_cast<cl_uint>(slot);

    const ProbeConstants pc = probe_constants(scene_, pair_, z, orientations_);
    const auto packed = pc.packed(+1);  // plane A
    rt_.queue().enqueueWriteBuffer(a_.consts, CL_TRUE, sizeof(float) * kProbeStride * slot,
                                   sizeof(float) * kProbeStride, packed.data());  // packed is local
    std::vector<float> mats;
    mats.reserve(static_cast<size_t>(frames) * plane_words(scene_));
    for (cl_uint f = 0; f < frames; ++f)
      append_plane_words(mats, scene_, pc, z, static_cast<int>(f));
    const auto first_plane = static_cast<cl_uint>(slot * frames);
    const cl::Event set_up = setup(a_.consts, mats, frames, first_plane, a_.tris, a_.vflags);
    MtsARowsBuffers rows_in;
    rows_in.probes = &a_.consts;
    rows_in.tris = &a_.tris;
    rows_in.vflags = &a_.vflags;
    rows_in.ref_tris = &a_.ref_tris;
    rows_in.ref_rows = &a_.ref_rows;
    rows_in.rows = &a_.rows;
    rows_in.codes = &a_.codes;
    MtsARowsArgs rows_args{};
    rows_args.area = area();
    rows_args.first_plane = first_plane;
    rows_args.per_probe = frames;
    rows_args.items = static_cast<cl_uint>(frames * a_row_groups(scene_));
    rows_args.use_ref = static_cast<cl_uint>(a_.has_ref);
    rows_args.fill_codes = static_cast<cl_uint>(fill_a_codes_);
    bind(a_rows_, rows_in, rows_args);
    cl::Event rows_done, bands_done;
    launch(a_rows_, primed_.a_rows, padded(frames * a_row_groups(scene_)), cl::NDRange(kLocal),
           &rows_done);
    if (!a_.has_ref) {  // this distance is the reference for the distances filled after it
      const size_t tri_bytes = sizeof(float) * frames * plane_floats_;
      const size_t row_bytes = sizeof(uint32_t) * frames * kh * row_words_;
      rt_.queue().enqueueCopyBuffer(a_.tris, a_.ref_tris, tri_bytes * slot, 0, tri_bytes);
      rt_.queue().enqueueCopyBuffer(a_.rows, a_.ref_rows, row_bytes * slot, 0, row_bytes);
      a_.has_ref = true;
    }
    MtsABandsBuffers bands_in;
    bands_in.probes = &a_.consts;
    bands_in.tris = &a_.tris;
    bands_in.vflags = &a_.vflags;
    bands_in.out = &a_.bands;
    MtsABandsArgs bands_args{};
    bands_args.area = area();
    bands_args.first_plane = first_plane;
    bands_args.per_probe = frames;
    bands_args.items = static_cast<cl_uint>(frames * bands());
    bind(a_bands_, bands_in, bands_args);
    launch(a_bands_, primed_.a_bands, padded(frames * bands()), cl::NDRange(kLocal), &bands_done);
    bands_done.wait();
    launches[i] = 3;
    kernel_seconds +=
        device_seconds(set_up) + device_seconds(rows_done) + device_seconds(bands_done);
  }
  return slots;
}

cl::Event MtsEvaluator::setup_plane_b(const std::vector<Probe>& probes,
                                      const std::vector<size_t>& active,
                                      const std::vector<cl_uint>& slots,
                                      const std::vector<int>& first_visited, int first_frame,
                                      int frames, cl::Buffer& probe_buf, cl::Buffer& slot_buf,
                                      cl::Buffer& tris, cl::Buffer& vflags) {
  std::vector<float> consts(active.size() * kProbeStride);
  std::vector<float> mats;
  mats.reserve(active.size() * frames * plane_words(scene_));
  std::vector<cl_uint> slot_and_start(2 * active.size());
  for (size_t i = 0; i < active.size(); ++i) {
    const Probe& p = probes[active[i]];
    const ProbeConstants pc = probe_constants(scene_, pair_, p.z, orientations_);
    const auto packed = pc.packed(-1);  // plane B
    std::copy(packed.begin(), packed.end(), consts.begin() + i * kProbeStride);
    const int start = first_visited[active[i]];
    for (int f = 0; f < frames; ++f)
      append_plane_words(mats, scene_, pc, p.z + p.s, (start + first_frame + f) % scene_.frames);
    slot_and_start[2 * i] = slots[i];
    slot_and_start[2 * i + 1] = static_cast<cl_uint>(start);
  }
  probe_buf = buffer_of(rt_.context(), consts);
  slot_buf = buffer_of(rt_.context(), slot_and_start);
  const size_t planes = active.size() * frames;
  tris = cl::Buffer(rt_.context(), CL_MEM_READ_WRITE, sizeof(float) * planes * plane_floats_);
  vflags = cl::Buffer(rt_.context(), CL_MEM_READ_WRITE, sizeof(uint32_t) * planes);
  return setup(probe_buf, mats, static_cast<cl_uint>(frames), 0, tris, vflags);
}

std::vector<std::vector<size_t>> MtsEvaluator::cache_groups(
    const std::vector<Probe>& probes) const {
  std::vector<std::vector<size_t>> groups;
  std::vector<double> zs;
  std::vector<bool> pending(probes.size(), true);
  for (size_t first = 0; first < probes.size(); ++first) {
    if (!pending[first]) continue;
    zs.clear();
    std::vector<size_t>& group = groups.emplace_back();
    for (size_t i = first; i < probes.size(); ++i) {
      if (!pending[i]) continue;
      const bool known = std::find(zs.begin(), zs.end(), probes[i].z) != zs.end();
      if (!known && zs.size() == a_.capacity) continue;
      if (!known) zs.push_back(probes[i].z);
      group.push_back(i);
      pending[i] = false;
    }
  }
  return groups;
}

std::vector<ProbeResult> MtsEvaluator::run(const std::vector<Probe>& probes) {
  std::vector<ProbeResult> results(probes.size());
  std::vector<Probe> fresh;
  std::vector<size_t> fresh_at;
  std::vector<double> repeated_z;
  for (size_t i = 0; i < probes.size(); ++i) {
    const auto it = full_runs_.find(plane_b_key(probes[i]));
    if (it == full_runs_.end()) {
      fresh.push_back(probes[i]);
      fresh_at.push_back(i);
      continue;
    }
    // the computation's result and work: its launches those of a probe that renders every frame
    // with plane A held (no cache filling); this run spent no time on it
    results[i] = it->second;
    results[i].launches = full_run_launches();
    results[i].seconds = results[i].kernel_seconds = 0;
    repeated_z.push_back(probes[i].z);
    ++repeats_;
  }
  // Their distances are still searched: plane A stays as recently used as if they were rendered,
  // so that a distance coming in evicts one whose search has ended.
  touch_plane_a(repeated_z);
  if (fresh.empty()) return results;
  std::vector<bool> decided;
  const std::vector<ProbeResult> computed = run_fresh(fresh, decided);
  for (size_t k = 0; k < fresh.size(); ++k) {
    results[fresh_at[k]] = computed[k];
    if (!decided[k]) full_runs_.emplace(plane_b_key(fresh[k]), computed[k]);
  }
  return results;
}

void MtsEvaluator::touch_plane_a(const std::vector<double>& zs) {
  ++a_.clock;
  for (const double z : zs) {
    const auto it = std::find(a_.z.begin(), a_.z.end(), z);
    if (it != a_.z.end()) a_.last_use[static_cast<size_t>(it - a_.z.begin())] = a_.clock;
  }
}

uint64_t MtsEvaluator::launches_per_batch() const {
  return shortcuts_ ? 3 : 2;  // set-up, band bounds (with shortcuts), raster
}

uint64_t MtsEvaluator::full_run_launches() const {
  uint64_t batches = 0;
  for (int done = 0; done < scene_.frames; done += batch_frames(done, scene_.frames)) ++batches;
  return batches * launches_per_batch();
}

std::pair<double, double> MtsEvaluator::plane_b_key(const Probe& probe) const {
  return {probe.z, plane_matrix_distance(scene_, probe.z + probe.s)};
}

std::vector<ProbeResult> MtsEvaluator::run_fresh(const std::vector<Probe>& probes,
                                                 std::vector<bool>& decided) {
  std::vector<ProbeResult> results(probes.size());
  decided.assign(probes.size(), false);
  reserve_plane_a(probes);
  std::vector<int> first_visited(probes.size(), 0);
  for (size_t i = 0; i < probes.size(); ++i) {
    const auto it = last_fight_frame_.find(probes[i].z);
    if (it != last_fight_frame_.end()) first_visited[i] = it->second;
  }
  // Probes whose distances fit in the plane-A cache at once go through the frames together.
  for (const std::vector<size_t>& group : cache_groups(probes))
    run_group(probes, group, first_visited, results, decided);
  finish_outcomes(results, decided);
  for (const auto& r : results) by_outcome_[static_cast<size_t>(r.outcome)] += r.fragment_pairs;
  return results;
}

void MtsEvaluator::run_group(const std::vector<Probe>& probes, const std::vector<size_t>& group,
                             const std::vector<int>& first_visited,
                             std::vector<ProbeResult>& results, std::vector<bool>& decided) {
  const auto kh = static_cast<cl_uint>(scene_.kernel_h);
  int done = 0;
  while (done < scene_.frames) {
    std::vector<size_t> active;
    for (const size_t i : group)
      if (!decided[i]) active.push_back(i);
    if (active.empty()) break;
    const int frames = batch_frames(done, scene_.frames);
    const auto t0 = std::chrono::steady_clock::now();
    double ksecs = 0;
    std::vector<int> cache_launches;
    const std::vector<cl_uint> slots = cache_plane_a(probes, active, ksecs, cache_launches);
    cl::Buffer probe_buf, slot_buf, tris, vflags;
    const cl::Event setup_done = setup_plane_b(probes, active, slots, first_visited, done, frames,
                                               probe_buf, slot_buf, tris, vflags);
    const size_t planes = active.size() * frames;
    const size_t items = planes * kh;
    const size_t band_items = planes * bands();
    cl::Buffer decided_bands(rt_.context(), CL_MEM_READ_WRITE,
                             sizeof(uint32_t) * band_items * decided_words_);
    cl::Event bounds_done;
    if (shortcuts_) {
      MtsFrameBoundsBuffers b;
      b.probes = &probe_buf;
      b.tris = &tris;
      b.vflags = &vflags;
      b.a_tris = &a_.tris;
      b.a_vflags = &a_.vflags;
      b.a_bands = &a_.bands;
      b.a_slots = &slot_buf;
      b.decided = &decided_bands;
      MtsFrameBoundsArgs args{};
      args.area = area();
      args.first_frame = static_cast<cl_uint>(done);
      args.frames_total = static_cast<cl_uint>(scene_.frames);
      args.frames = static_cast<cl_uint>(frames);
      args.items = static_cast<cl_uint>(band_items);
      bind(bounds_, b, args);
      launch(bounds_, primed_.bounds, padded(band_items), cl::NDRange(kLocal), &bounds_done);
    } else {
      rt_.queue().enqueueFillBuffer(decided_bands, cl_uint{0}, 0,
                                    sizeof(uint32_t) * band_items * decided_words_, nullptr,
                                    &bounds_done);
    }
    std::vector<uint32_t> rows(items);
    cl::Buffer result(rt_.context(), CL_MEM_WRITE_ONLY, sizeof(uint32_t) * items);
    MtsRasterBuffers rb;
    rb.probes = &probe_buf;
    rb.tris = &tris;
    rb.vflags = &vflags;
    rb.a_tris = &a_.tris;
    rb.a_vflags = &a_.vflags;
    rb.a_rows = &a_.rows;
    rb.a_slots = &slot_buf;
    rb.a_codes = &a_.codes;
    rb.decided = &decided_bands;
    rb.result = &result;
    MtsRasterArgs ra{};
    ra.area = area();
    ra.first_frame = static_cast<cl_uint>(done);
    ra.frames_total = static_cast<cl_uint>(scene_.frames);
    ra.frames = static_cast<cl_uint>(frames);
    ra.shortcuts = static_cast<cl_uint>(shortcuts_);
    ra.a_codes_filled = static_cast<cl_uint>(fill_a_codes_);
    bind(raster_, rb, ra);
    cl::Event raster_done;
    launch(raster_, primed_.raster,
           cl::NDRange(padded_size(bands()), static_cast<size_t>(frames), active.size()),
           cl::NDRange(kLocal, 1, 1), &raster_done);
    rt_.queue().enqueueReadBuffer(result, CL_TRUE, 0, sizeof(uint32_t) * items, rows.data());
    for (const uint32_t v : rows) {
      if (v & kBounds)
        by_bounds_ += v >> kCountShift;
      else if (v >> kCountShift)
        ++rows_rasterised_;
      if (v & kReused) ++rows_reused_;
    }
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ksecs += device_seconds(setup_done) + device_seconds(bounds_done) + device_seconds(raster_done);
    wall_seconds_ += secs;
    kernel_seconds_ += ksecs;

    const std::vector<uint64_t> probe_pairs =
        fold_launch(rows, active, done, frames, kh, results, decided, after_decision_);
    for (const size_t i : active)
      if (decided[i]) {  // a fight or a non-finite frame: the next probes of this distance
                         // start there
        results[i].deciding_frame = (first_visited[i] + results[i].frames - 1) % scene_.frames;
        last_fight_frame_[probes[i].z] = results[i].deciding_frame;
      }
    uint64_t launch_pairs = 0;
    for (const uint64_t n : probe_pairs) launch_pairs += n;
    for (size_t i = 0; i < active.size(); ++i) {
      const double share =
          launch_pairs ? static_cast<double>(probe_pairs[i]) / static_cast<double>(launch_pairs)
                       : 1.0 / static_cast<double>(active.size());
      results[active[i]].seconds += secs * share;
      results[active[i]].kernel_seconds += ksecs * share;
      // set-up, bounds and raster, and the plane-A cache's launches when this batch filled it
      results[active[i]].launches += launches_per_batch() + cache_launches[i];
    }
    pairs_ += launch_pairs;
    done += frames;
  }
}

}  // namespace depthprec
