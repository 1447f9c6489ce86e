#include "host/cli/scene_options.h"

#include <fmt/format.h>

#include <set>

#include "host/errors.h"

namespace depthprec::cli {

void SceneOptions::add_to(CLI::App& cmd, bool with_pairs) {
  cmd.add_option("scene", scene_file,
                 "Scene file (JSON); fields it leaves out come from the embedded default "
                 "data/gilg2021.json (Gilg et al. 2021)");
  cmd.add_option("--set", sets,
                 "Override any scene field: --set near=0.1 --set pipeline.divide=exact "
                 "--set kernel=[50,50]");
  if (with_pairs) {
    cmd.add_option("-t,--technique", techniques, "Technique(s): " + technique_names())
        ->delimiter(',');
    cmd.add_option("-f,--format", formats,
                   "Storage format(s): unorm<b>, float16, float24, float32, e<E>m<M>")
        ->delimiter(',');
    cmd.add_option("--depth-range", depth_ranges, "gl and/or zero_to_one")->delimiter(',');
  }
  cmd.add_option("--distances", distances, "Eye distances of plane A, e.g. 2,1024,1e6")
      ->delimiter(',');
  cmd.add_option("--near", near, "Near plane distance");
  cmd.add_option("--far", far, "Far plane distance (inf for none)");
  cmd.add_option("--kernel", kernel, "Measurement kernel WxH in pixels (viewport follows)");
  cmd.add_option("--frames", frames, "Animation frames per probe");
  cmd.add_option("--fov", fov, "Vertical field of view in degrees");
  cmd.add_option("--rel-precision", rel_precision, "Stop bisecting at (hi-lo)/hi <= this");
  cmd.add_option("--matrix-precision", matrix_precision, "float or double");
  cmd.add_option("--compose", compose, "separate: P*(MV*v); premultiplied: (P*MV)*v");
  cmd.add_option("--divide", divide, "reciprocal: z*fl(1/w); exact: z/w");
  cmd.add_option("--rounding", rounding, "Storage rounding: nearest_even or truncate");
  cmd.add_option("--denormals", denormals, "keep or flush");
  cmd.add_option("--log-k", log_k, "k of the log techniques");
}

Scene SceneOptions::load() const {
  std::vector<std::string> all;
  auto set_if = [&all](const std::string& key, const std::string& v) {
    if (!v.empty()) all.push_back(key + "=" + v);
  };
  set_if("near", near);
  set_if("far", far == "inf" ? "\"inf\"" : far);
  if (!kernel.empty()) {
    int w = 0, h = 0;
    char tail = 0;
    if (std::sscanf(kernel.c_str(), "%dx%d%c", &w, &h, &tail) != 2)
      throw Error(ExitCode::usage,
                  fmt::format("--kernel '{}': expected WxH in pixels, e.g. 200x200", kernel));
    set_if("kernel", fmt::format("[{},{}]", w, h));
    set_if("viewport", fmt::format("[{},{}]", w, h));
  }
  set_if("frames", frames);
  set_if("fov_y_deg", fov);
  set_if("rel_precision", rel_precision);
  set_if("pipeline.matrix_precision", matrix_precision);
  set_if("pipeline.compose", compose);
  set_if("pipeline.divide", divide);
  set_if("pipeline.rounding", rounding);
  set_if("pipeline.denormals", denormals);
  set_if("log_k", log_k);
  if (!distances.empty()) {
    std::string list;
    for (const auto& d : distances) list += (list.empty() ? "" : ",") + d;
    set_if("distances", "[" + list + "]");
  }
  all.insert(all.end(), sets.begin(), sets.end());
  Scene scene = load_scene(scene_file, all);
  if (!techniques.empty() || !formats.empty() || !depth_ranges.empty()) {
    std::vector<std::string> ts = techniques, fs = formats;
    std::set<std::string> seen_t, seen_f;
    for (const auto& p : scene.evaluate) {
      if (techniques.empty() && seen_t.insert(info(p.technique).name).second)
        ts.push_back(info(p.technique).name);
      if (formats.empty() && seen_f.insert(p.format).second) fs.push_back(p.format);
    }
    std::vector<DepthRange> rs;
    for (const auto& r : depth_ranges) rs.push_back(parse_depth_range(r));
    if (rs.empty()) rs.push_back(scene.pipeline.depth_range);
    scene.evaluate.clear();
    scene.json["evaluate"] = nlohmann::json::array();
    for (const auto& t : ts)
      for (const auto& f : fs)
        for (const auto r : rs) {
          StorageFormat::parse(f);
          scene.evaluate.push_back({parse_technique(t), f, r});
          // the scene a header records is the one that ran
          scene.json["evaluate"].push_back({{"technique", t}, {"format", f}, {"depth_range", to_string(r)}});
        }
  }
  return scene;
}

void OutputOptions::add_to(CLI::App& cmd) {
  cmd.add_option("--format-out", format_out, "text (default), csv, json or markdown")
      ->check(CLI::IsMember({"text", "csv", "json", "markdown"}));
  cmd.add_option("-o,--output", output, "Write to this file instead of standard output");
  cmd.add_flag("--no-timing", no_timing,
               "Leave measured times out, so two runs' outputs compare byte for byte");
}

void BatchOptions::add_to(CLI::App& cmd, const std::string& units) {
  cmd.add_flag("--resume", resume,
               "Continue an interrupted run: rows in FILE.rows.jsonl (beside --output FILE) are kept, "
               "the rest computed");
  cmd.add_option("--shard", shard,
                 "Compute part i of N (i/N): " + units +
                     " k with k mod N = i - 1. Join the parts' JSON outputs with `depthprec merge`");
}

}  // namespace depthprec::cli
