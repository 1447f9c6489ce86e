#include "host/render/render_run.h"

#include <fmt/format.h>

#include <chrono>

#include "host/mts/mts_search.h"
#include "host/mts/row_json.h"
#include "host/mts/worst_case.h"
#include "host/render/driver_settings.h"
#include "host/render/gl_depth_format.h"
#include "host/render/render_evaluator.h"

namespace depthprec {

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
    RenderEvaluator ev(gl, scene, pair);
    const auto mark = [](MtsRow r) {
      r.frames_per_second = r.seconds > 0 ? static_cast<double>(r.frames) / r.seconds : 0;
      return r;
    };
    const bool worst_case = scene.sampling == Sampling::worst_case;
    uint64_t frames = 0;  // the pair's frames drawn (and their seconds), over every evaluator
    double seconds = 0;
    auto rows = search_pair(
        ev, scene, pair, zs,
        [&](const MtsRow& r) {
          if (control.on_row && !worst_case) control.on_row(mark(r));
        },
        control.stop);
    frames += ev.frames_rendered();
    seconds += ev.seconds();
    // The driver draws the worst case's rounds of orientations as the emulator samples them.
    if (worst_case) {
      refine_worst_case(
          [&](const Scene& s, const Orientations& o,
              const std::function<void(ProbeEvaluator&)>& use) {
            RenderEvaluator round_ev(gl, s, pair, o);
            use(round_ev);
            frames += round_ev.frames_rendered();
            seconds += round_ev.seconds();
          },
          scene, pair, rows, control.stop);
      if (control.on_row)
        for (const auto& r : rows) control.on_row(mark(r));
    }
    for (auto& r : rows) {
      r = mark(r);
      run.info.fragment_pairs += r.fragment_pairs;
      run.info.evaluated_pairs += r.fragment_pairs;
    }
    if (log)
      log(fmt::format(
          "{}: {} distances, {} frames rendered in {:.2f} s ({:.0f} frames/s), depth "
          "buffer {}",
          pair.label(), rows.size(), frames, seconds,
          seconds > 0 ? static_cast<double>(frames) / seconds : 0.0, ev.depth_format().given()));
    run.rows.insert(run.rows.end(), rows.begin(), rows.end());
  }
  sort_rows(scene, run.rows);
  run.info.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

}  // namespace depthprec
