#include "host/render/render_run.h"

#include <fmt/format.h>

#include <chrono>
#include <cstdint>
#include <memory>

#include "host/mts/row_json.h"
#include "host/mts/worst_case.h"
#include "host/render/driver_settings.h"
#include "host/render/gl_depth_format.h"
#include "host/render/render_evaluator.h"

namespace depthprec {

namespace {

// The driver's evaluators on the one context; the frames they drew and their seconds, the pair's.
class RenderSource : public EvaluatorSource<ProbeEvaluator> {
 public:
  RenderSource(GlContext& gl, const EvalPair& pair) : gl_(gl), pair_(pair) {}
  std::unique_ptr<ProbeEvaluator> make(const Scene& scene, const Orientations& o) override {
    return std::make_unique<RenderEvaluator>(gl_, scene, pair_, o);
  }
  void retire(ProbeEvaluator& ev) override {
    const auto& r = static_cast<const RenderEvaluator&>(ev);  // as make built it
    frames += r.frames_rendered();
    read_backs += r.read_backs();
    seconds += r.seconds();
  }
  uint64_t frames = 0, read_backs = 0;  // over every evaluator
  double seconds = 0;

 private:
  GlContext& gl_;
  const EvalPair& pair_;
};

}  // namespace

std::map<std::string, std::string> check_scene_renders(const Scene& scene) {
  check_renderable(scene);
  std::map<std::string, std::string> out;
  for (const auto& pair : scene.evaluate) {
    const GlDepthFormat f = gl_depth_format(pair.format);
    out[pair.format] = fmt::format("{} ({})", f.given(), f.gl_name);
  }
  return out;
}

Scene rendered_counterpart(const Scene& scene) {
  Scene s = scene;
  for (const DriverSetting& d : driver_settings())
    if (d.reset) d.reset(s.pipeline);
  return s;
}

MtsRun render_scene(GlContext& gl, const Scene& scene,
                    const std::function<void(const std::string&)>& log, const RunControl& control) {
  MtsRun run;
  run.info.device = gl.description();
  const auto t0 = std::chrono::steady_clock::now();
  const size_t nd = scene.distances.size();
  for (size_t p = 0; p < scene.evaluate.size(); ++p) {
    const EvalPair& pair = scene.evaluate[p];
    std::vector<double> zs;
    for (size_t d = 0; d < nd; ++d) {
      const size_t k = p * nd + d;
      if (static_cast<int>(k % static_cast<size_t>(control.shard_count)) != control.shard_index)
        continue;
      if (!control.done.count(row_key(pair, scene.distances[d]))) zs.push_back(scene.distances[d]);
    }
    if (zs.empty()) continue;
    const auto mark = [](MtsRow r) {
      r.frames_per_second = r.seconds > 0 ? static_cast<double>(r.frames) / r.seconds : 0;
      return r;
    };
    // The driver draws the worst case's rounds of orientations as the emulator samples them.
    RenderSource source(gl, pair);
    auto rows = search_sampled(
        source, scene, pair, zs,
        [&](const MtsRow& r) {
          if (control.on_row) control.on_row(mark(r));
        },
        control.stop);
    for (auto& r : rows) {
      r = mark(r);
      run.info.fragment_pairs += r.fragment_pairs;
      run.info.evaluated_pairs += r.fragment_pairs;
    }
    if (log)
      log(fmt::format(
          "{}: {} distances, {} frames rendered in {:.2f} s ({:.0f} frames/s), depth "
          "buffer {}",
          pair.label(), rows.size(), source.frames, source.seconds,
          source.seconds > 0 ? static_cast<double>(source.frames) / source.seconds : 0.0,
          gl_depth_format(pair.format).given()));
    run.rows.insert(run.rows.end(), rows.begin(), rows.end());
    // The run's own counters, as the rows' (docs/cli.md): read-back rounds and the driver's time.
    run.info.launches += source.read_backs;
    run.info.kernel_seconds += source.seconds;
  }
  sort_rows(scene, run.rows);
  run.info.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

}  // namespace depthprec
