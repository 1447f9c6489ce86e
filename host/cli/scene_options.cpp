#include "host/cli/scene_options.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "host/base/errors.h"
#include "host/model/profile.h"

namespace depthprec::cli {

void SceneOptions::add_to(CLI::App& cmd, bool with_pairs) {
  cmd.add_option("scene", scene_file,
                 "Scene file (JSON); fields it leaves out come from the embedded default "
                 "data/gilg2021.json (Gilg et al. 2021)");
  cmd.add_option("--set", sets,
                 "Override any scene field: --set near=0.1 --set pipeline.divide=exact "
                 "--set rotation_range_deg=2 (a kernel smaller than the viewport sees only the "
                 "planes' centre: "
                 "use --kernel, which sets both)");
  if (with_pairs) {
    cmd.add_option("-t,--technique", techniques, "Technique(s): " + technique_names())
        ->delimiter(',');
    cmd.add_option("-f,--format", formats,
                   "Storage format(s): unorm<b>, float16, float24, float32, e<E>m<M>")
        ->delimiter(',');
    cmd.add_option("--depth-range", depth_ranges, "gl and/or zero_to_one")->delimiter(',');
  }
  // Split here rather than by CLI11's delimiter, which drops empty entries ("1,,2").
  cmd.add_option("--distances", distances,
                 "Eye distances of plane A, each once, in any order, e.g. 2,1024,1e6");
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
  cmd.add_option(
      "--profile", profile,
      "Implementation profile: ideal (docs/spec.md 2), llvmpipe (Mesa's fused vertex "
      "products, log, clip stage, depth-plane set-up, FMA viewport and unorm "
      "conversions), softpipe (llvmpipe's vertex stage, its own quad-stepped planes "
      "and truncated unorm codes), gles_mediump (binary16 shaders), gles2_highp (the GLSL ES "
      "1.00 highp minimum), or an "
      "API envelope's adversary: d3d11, vulkan_min (bounded under the envelope's "
      "model); `depthprec pipelines` lists them");
}

namespace {

// A number as the user typed it: the whole text, finite (or "inf" where allowed); the error
// names the option.
std::string number_text(const std::string& option, const std::string& v, bool allow_inf = false) {
  if (allow_inf && v == "inf") return "\"inf\"";
  size_t used = 0;
  double d = 0;
  try {
    d = std::stod(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (v.empty() || used != v.size() || !std::isfinite(d))
    throw Error(ExitCode::usage, fmt::format("{} '{}': expected a finite number{}", option, v,
                                             allow_inf ? " or inf" : ""));
  return v;
}

std::string whole_number_text(const std::string& option, const std::string& v) {
  const size_t sign =
      !v.empty() && v[0] == '-' ? 1 : 0;  // a negative count is a range error, named by the scene
  const bool digits =
      v.size() > sign && v.find_first_not_of("0123456789", sign) == std::string::npos;
  if (!digits)
    throw Error(ExitCode::usage,
                fmt::format("{} '{}': expected a whole number, e.g. 20", option, v));
  return v;
}

// A far plane given on the command line that some pairs have no use for: said once (a command
// that loads the scene once per profile would say it again), so a user who set it for those
// pairs learns that it changed nothing there.
void note_unused_far(const Scene& scene, const std::string& given) {
  std::vector<std::string> unused;
  for (const auto& p : scene.evaluate) {
    const std::string name = info(p.technique).name;
    if (!has_far_plane(p.technique) &&
        std::find(unused.begin(), unused.end(), name) == unused.end())
      unused.push_back(name);
  }
  static std::set<std::string> said;
  if (unused.empty() || !said.insert(given).second) return;
  std::fprintf(stderr, "depthprec: note: %s: %s %s no far plane, so it changes nothing there\n",
               given.c_str(), fmt::format("{}", fmt::join(unused, ", ")).c_str(),
               unused.size() == 1 ? "has" : "have");
}

}  // namespace

bool SceneOptions::any() const {
  for (const std::string* v :
       {&scene_file, &near, &far, &kernel, &frames, &rel_precision, &matrix_precision, &compose,
        &divide, &rounding, &denormals, &log_k, &fov, &profile})
    if (!v->empty()) return true;
  return !sets.empty() || !techniques.empty() || !formats.empty() || !depth_ranges.empty() ||
         !distances.empty();
}

namespace {

struct NamedSets {
  std::vector<std::string> all;
  std::map<std::string, std::string> origins;

  void add(const std::string& option, const std::string& key, const std::string& user,
           const std::string& json) {
    if (user.empty()) return;
    all.push_back(key + "=" + json);
    origins[key] = option + " " + user;
  }
};

std::string kernel_size_json(const std::string& kernel) {
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(kernel.c_str(), "%dx%d%c", &w, &h, &tail) != 2)
    throw Error(ExitCode::usage,
                fmt::format("--kernel '{}': expected WxH in pixels, e.g. 200x200", kernel));
  return fmt::format("[{},{}]", w, h);
}

// *typed: the entries as the user typed them, for messages.
std::string distances_json(const std::vector<std::string>& distances, std::string* typed) {
  std::string list;
  std::vector<std::string> entries;
  for (const auto& token : distances) {
    std::stringstream ss(token);
    std::string d;
    while (std::getline(ss, d, ',')) entries.push_back(d);
    if (token.empty() || token.back() == ',') entries.push_back("");
  }
  for (const auto& d : entries) {
    if (d.empty())
      throw Error(ExitCode::usage,
                  fmt::format("--distances: an empty entry in '{}'; separate distances "
                              "by single commas, e.g. 2,1024,1e6",
                              fmt::join(distances, ",")));
    list += (list.empty() ? "" : ",") + number_text("--distances", d);
    *typed += (typed->empty() ? "" : ",") + d;
  }
  return "[" + list + "]";
}

void add_named_options(const SceneOptions& o, NamedSets& named) {
  named.add("--near", "near", o.near, o.near.empty() ? "" : number_text("--near", o.near));
  named.add("--far", "far", o.far, o.far.empty() ? "" : number_text("--far", o.far, true));
  if (!o.kernel.empty()) {
    const std::string size = kernel_size_json(o.kernel);
    named.add("--kernel", "kernel", o.kernel, size);
    named.add("--kernel", "viewport", o.kernel, size);
  }
  named.add("--frames", "frames", o.frames,
            o.frames.empty() ? "" : whole_number_text("--frames", o.frames));
  named.add("--fov", "fov_y_deg", o.fov, o.fov.empty() ? "" : number_text("--fov", o.fov));
  named.add("--rel-precision", "rel_precision", o.rel_precision,
            o.rel_precision.empty() ? "" : number_text("--rel-precision", o.rel_precision));
  named.add("--matrix-precision", "pipeline.matrix_precision", o.matrix_precision,
            o.matrix_precision);
  named.add("--compose", "pipeline.compose", o.compose, o.compose);
  named.add("--divide", "pipeline.divide", o.divide, o.divide);
  named.add("--rounding", "pipeline.rounding", o.rounding, o.rounding);
  named.add("--denormals", "pipeline.denormals", o.denormals, o.denormals);
  named.add("--log-k", "log_k", o.log_k, o.log_k.empty() ? "" : number_text("--log-k", o.log_k));
  // --profile is pipeline.profile (the scene applies its settings); the keys it settles are
  // named here too, so a --set of one of them is refused as a key given twice.
  named.add("--profile", "pipeline.profile", o.profile, o.profile);
  if (!o.profile.empty())
    for (const std::string& set : depthprec::profile(o.profile).sets)
      named.origins[set.substr(0, set.find('='))] = "--profile " + o.profile;
  if (!o.distances.empty()) {
    std::string typed;
    const std::string list = distances_json(o.distances, &typed);
    named.add("--distances", "distances", typed, list);
  }
}

// What the user typed wins over what the command implies.
void add_implied(const SceneOptions& o, NamedSets& named) {
  const auto user_sets = [&o](const std::string& key) {
    for (const auto& set : o.sets)
      if (set.substr(0, set.find('=')) == key) return true;
    return false;
  };
  for (const auto& [set, origin] : o.implied) {
    const std::string key = set.substr(0, set.find('='));
    if (named.origins.count(key) || user_sets(key)) continue;
    named.all.push_back(set);
    named.origins[key] = origin;
  }
}

void check_set_once(const std::vector<std::string>& sets,
                    const std::map<std::string, std::string>& origins) {
  // One key, or a block and a key inside it (pipeline and pipeline.divide).
  const auto overlap = [](const std::string& a, const std::string& b) {
    return a == b || a.rfind(b + ".", 0) == 0 || b.rfind(a + ".", 0) == 0;
  };
  for (size_t i = 0; i < sets.size(); ++i) {
    const std::string key = sets[i].substr(0, sets[i].find('='));
    for (const auto& [k, option] : origins)
      if (overlap(k, key))
        throw Error(ExitCode::usage,
                    fmt::format("{} and --set {} both set '{}': give it once", option, sets[i], k));
    for (size_t j = 0; j < i; ++j) {
      const std::string earlier = sets[j].substr(0, sets[j].find('='));
      if (overlap(earlier, key))
        throw Error(ExitCode::usage,
                    fmt::format("--set {} and --set {} both set '{}': give it once", sets[j],
                                sets[i], earlier));
    }
  }
}

// --technique/--format/--depth-range: the scene's pairs replaced by their cross product, the
// scene's own techniques or formats standing in for the option not given.
void replace_pairs(const SceneOptions& o, Scene& scene) {
  std::vector<std::string> ts = o.techniques, fs = o.formats;
  std::set<std::string> seen_t, seen_f;
  for (const auto& p : scene.evaluate) {
    if (o.techniques.empty() && seen_t.insert(info(p.technique).name).second)
      ts.push_back(info(p.technique).name);
    if (o.formats.empty() && seen_f.insert(p.format).second) fs.push_back(p.format);
  }
  std::vector<DepthRange> rs;
  for (const auto& r : o.depth_ranges) rs.push_back(parse_depth_range(r));
  scene.evaluate.clear();
  scene.json["evaluate"] = nlohmann::json::array();
  for (const auto& t : ts)
    for (const auto& f : fs) {
      StorageFormat::parse(f);
      const Technique tech = parse_technique(t);
      // No --depth-range: each technique in the scene's range, or its own when the scene names
      // none.
      for (const auto r : rs.empty() ? std::vector<DepthRange>{scene.range_for(tech)} : rs) {
        scene.evaluate.push_back({tech, f, r});
        // the scene a header records is the one that ran
        scene.json["evaluate"].push_back(
            {{"technique", t}, {"format", f}, {"depth_range", to_string(r)}});
      }
    }
}

std::string far_option(const std::vector<std::string>& sets,
                       const std::map<std::string, std::string>& origins) {
  std::string far_given = origins.count("far") ? origins.at("far") : "";
  for (const auto& set : sets)
    if (set.rfind("far=", 0) == 0) far_given = "--set " + set;
  return far_given;
}

}  // namespace

void refuse_unused(CLI::App& cmd, const std::vector<std::string>& names, const std::string& why) {
  for (const std::string& name : names) {
    CLI::Option* o = cmd.get_option(name);
    o->group("");  // CLI11: an empty group hides the option from --help
    o->check([name, why, &cmd](const std::string&) -> std::string {
      throw Error(ExitCode::usage,
                  fmt::format("{}: {} has no effect: {}; drop it", cmd.get_name(), name, why));
    });
  }
}

Scene SceneOptions::load() const {
  // Every named option is a --set in disguise; `origins` lets the scene's errors name the option
  // the user typed, and a key set twice (--near 0.1 --set near=5) is refused rather than one
  // silently winning.
  NamedSets named;
  add_named_options(*this, named);
  add_implied(*this, named);
  check_set_once(sets, named.origins);
  named.all.insert(named.all.end(), sets.begin(), sets.end());
  Scene scene;
  try {
    scene = load_scene(scene_file, named.all, false, named.origins);
  } catch (const InputError& e) {
    // A second word after an option lands here (each option takes one value).
    const bool path_like = scene_file.find_first_of("./") != std::string::npos;
    if (scene_file.empty() || path_like || std::ifstream(scene_file).good()) throw;
    throw InputError(std::string(e.what()) +
                     " (the scene positional; each option takes one value: list several with "
                     "commas, e.g. -t standard,reversed, or repeat the option)");
  }
  if (!techniques.empty() || !formats.empty() || !depth_ranges.empty()) {
    replace_pairs(*this, scene);
    // Other pairs are another scene, as a --set makes one.
    scene.name = changed_scene_name(scene.name);
    scene.json["name"] = scene.name;
  }
  check_pairs(scene);
  check_planes_cover_kernel(scene);
  const std::string far_given = far_option(sets, named.origins);
  if (!far_given.empty()) note_unused_far(scene, far_given);
  return scene;
}

std::string format_of_extension(const std::string& path) {
  const auto dot = path.rfind('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "json") return "json";
  if (ext == "csv") return "csv";
  if (ext == "md" || ext == "markdown") return "markdown";
  if (ext == "txt") return "text";
  return "";
}

void OutputOptions::add_to(CLI::App& cmd) {
  CLI::Option* chosen =
      cmd.add_option("--format-out", format_out,
                     "text, csv, json or markdown (default: from the --output file's extension "
                     ".txt, .csv, .json or .md, else text)")
          ->check(CLI::IsMember({"text", "csv", "json", "markdown"}));
  cmd.add_option("-o,--output", output, "Write to this file instead of standard output");
  cmd.add_flag("--no-timing", no_timing,
               "Leave measured times out, so two runs' outputs compare byte for byte");
  // Runs once the command line is parsed, before the command: -o out.json writes JSON unless
  // --format-out says otherwise, and then the mismatch is pointed out.
  cmd.parse_complete_callback([this, chosen]() {
    const std::string by_name = format_of_extension(output);
    if (by_name.empty()) return;
    if (chosen->count() == 0)
      format_out = by_name;
    else if (format_out != by_name)
      std::fprintf(
          stderr,
          "depthprec: note: --output %s gets --format-out %s, not the %s its name suggests\n",
          output.c_str(), format_out.c_str(), by_name.c_str());
  });
}

void BatchOptions::add_to(CLI::App& cmd, const std::string& units) {
  cmd.add_flag(
      "--resume", resume,
      "Continue an interrupted run: rows in FILE.rows.jsonl (beside --output FILE) are kept, "
      "the rest computed");
  cmd.add_option(
      "--shard", shard,
      "Compute part i of N (i/N): " + units +
          " k with k mod N = i - 1. Join the parts' JSON outputs with `depthprec merge`");
}

}  // namespace depthprec::cli
