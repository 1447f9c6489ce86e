// bias: the smallest depth bias (polygon offset) that lets a coplanar overlay win the depth test
// everywhere, per pair and distance, as an API applies it (host/bias/, docs/bias.md). A record
// batch: one record per pair holding its distances' rows, so it journals, resumes, shards and
// merges as advise does.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>

#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/bias/bias_evaluator.h"
#include "host/bias/bias_search.h"
#include "host/bias/bias_worst_case.h"
#include "host/cli/commands.h"
#include "host/cli/record_batch.h"
#include "host/cli/scene_options.h"
#include "host/model/profile.h"
#include "host/model/tilt_limit.h"
#include "host/mts/worst_case.h"
#include "host/output/output_guard.h"
#include "host/output/report.h"
#include "host/output/text_table.h"
#include "host/render/gl_context.h"
#include "host/render/render_bias.h"
#include "host/render/render_evaluator.h"
#include "host/render/render_run.h"

namespace depthprec::cli {

namespace {

struct BiasCliOptions {
  SceneOptions scene;
  OutputOptions out;
  BatchOptions batch;
  std::string api = "gl", r_unorm, representation = "format", slope = "max";
  double clamp = 0, tilt = 0, set_factor = 1;
  bool or_equal = false;
  std::string source = "emulated", gl_device = GlDeviceChoice{}.text;
};

// Rendered probes take the driver's r, slope and bias arithmetic, so the options that choose
// them are refused rather than silently ignored.
void check_rendered_options(const BiasCliOptions& o) {
  if (o.api != "gl")
    throw InputError(fmt::format(
        "--api {}: --source rendered renders through OpenGL, whose glPolygonOffset is gl's rule",
        o.api));
  if (!o.r_unorm.empty())
    throw InputError(
        "--r-unorm: with --source rendered the driver decides r (compare with "
        "--source emulated --r-unorm ...)");
  if (o.slope != "max")
    throw InputError("--slope: with --source rendered the driver decides the slope form");
}

// A clamp of the other sign than a pair's bias never binds (the APIs' rule: a positive clamp
// limits positive offsets only), so that pair runs as without it: said, not left to be guessed.
void note_clamp_without_effect(const Scene& scene, const BiasOptions& b) {
  if (b.clamp == 0) return;
  std::vector<std::string> unaffected;
  for (const EvalPair& pair : scene.evaluate)
    if (bias_not_applicable(scene, pair).empty() && !clamp_binds(b.clamp, bias_sign(scene, pair)))
      unaffected.push_back(pair.label());
  if (unaffected.empty()) return;
  fmt::print(stderr,
             "depthprec: note: --clamp {} has no effect on {}: their bias is {} (it moves the "
             "overlay toward the camera under {}), and a {} clamp limits only {} offsets "
             "(D3D, Vulkan and OpenGL: min(offset, clamp) for a clamp > 0, max(offset, clamp) "
             "for one < 0); --clamp {} limits them\n",
             human(b.clamp), fmt::join(unaffected, ", "), b.clamp > 0 ? "negative" : "positive",
             b.clamp > 0 ? "LESS" : "GREATER", b.clamp > 0 ? "positive" : "negative",
             b.clamp > 0 ? "positive" : "negative", human(-b.clamp));
}

BiasOptions bias_options_of(const BiasCliOptions& o) {
  BiasOptions b;
  b.api = parse_bias_api(o.api);
  if (!o.r_unorm.empty())
    b.unorm_r = parse_unorm_r(o.r_unorm);
  else if (!o.scene.profile.empty() && o.source == "emulated") {  // the profile's choice of r
    const Profile& p = profile(o.scene.profile);
    const char* r = p.bias_unorm_r;
    for (const std::string& set : p.sets)
      if (const auto [key, value] = pipeline_setting(set); key == "envelope" && value != "none")
        throw InputError(fmt::format(
            "--profile {0}: an API envelope's adversary moves one plane against another, and a "
            "bias overlay lies on its own plane: bias has no {0} emulation (measure under ideal, "
            "llvmpipe or softpipe; --set bound_model={0} gives the units guaranteed under {0})",
            o.scene.profile));
    if (!r)
      throw InputError(fmt::format(
          "--profile {}: its depth bias is not modelled (no rule of --r-unorm is the driver's); "
          "choose one with --r-unorm",
          o.scene.profile));
    b.unorm_r = parse_unorm_r(r);
  }
  b.representation = parse_vulkan_representation(o.representation);
  b.slope = parse_slope_form(o.slope);
  b.clamp = o.clamp;
  b.tilt_deg = o.tilt;
  b.set_factor = o.set_factor;
  b.or_equal = o.or_equal;
  validate(b);
  return b;
}

// The emulated bias evaluators of a pair.
class EmulatedBias : public EvaluatorSource<BiasEvaluator> {
 public:
  EmulatedBias(OpenClRuntime& rt, const EvalPair& pair, const BiasOptions& b)
      : rt_(rt), pair_(pair), b_(b) {}
  std::unique_ptr<BiasEvaluator> make(const Scene& s, const Orientations& o) override {
    return std::make_unique<BiasEmulator>(rt_, s, pair_, b_, o);
  }

 private:
  OpenClRuntime& rt_;
  const EvalPair& pair_;
  const BiasOptions& b_;
};

// A rendered bias evaluator with the renderer it draws on.
class OwnedBiasRenderer : public BiasEvaluator {
 public:
  OwnedBiasRenderer(GlContext& gl, const Scene& s, const EvalPair& pair, const Orientations& o,
                    const BiasOptions& b)
      : renderer_(gl, s, pair, o), bias_(renderer_, b) {}
  std::vector<ProbeResult> run(const std::vector<BiasProbe>& probes) override {
    return bias_.run(probes);
  }
  RowSource source() const override { return bias_.source(); }

 private:
  RenderEvaluator renderer_;
  BiasRenderer bias_;
};

// The rendered bias evaluators of a pair.
class RenderedBias : public EvaluatorSource<BiasEvaluator> {
 public:
  RenderedBias(GlContext& gl, const EvalPair& pair, const BiasOptions& b)
      : gl_(gl), pair_(pair), b_(b) {}
  std::unique_ptr<BiasEvaluator> make(const Scene& s, const Orientations& o) override {
    return std::make_unique<OwnedBiasRenderer>(gl_, s, pair_, o, b_);
  }

 private:
  GlContext& gl_;
  const EvalPair& pair_;
  const BiasOptions& b_;
};

// One pair's record: its rows, or why the bias does not apply. gl: the probes are rendered
// through it (no MTS column: rendering its search too would take minutes, `depthprec render`
// measures it); null: emulated, with the pair's MTS beside each answer.
nlohmann::json bias_record(OpenClRuntime& rt, GlContext* gl, const Scene& scene,
                           const EvalPair& pair, const BiasOptions& b) {
  nlohmann::json rec = pair.fields();
  const std::string why = bias_not_applicable(scene, pair);
  rec["applicable"] = why.empty();
  if (!why.empty()) {
    rec["reason"] = why;
    rec["rows"] = nlohmann::json::array();
    return rec;
  }
  std::vector<double> mts(scene.distances.size(), std::numeric_limits<double>::quiet_NaN());
  // Under worst-case sampling the answers hold in every orientation sampled, as the MTS does.
  if (gl) {
    RenderedBias source(*gl, pair, b);
    rec["rows"] = bias_rows(scene, pair, b, RowSource::rendered, scene.distances,
                            search_bias_sampled(source, scene, pair, b, scene.distances), mts);
    return rec;
  }
  // The MTS beside each answer: what separation the pair resolves there without any bias.
  {
    const auto rows = search_sampled(rt, scene, pair, scene.distances);
    for (size_t k = 0; k < rows.size(); ++k)
      if (rows[k].verdict() == Verdict::resolved) mts[k] = rows[k].mts;
  }
  EmulatedBias source(rt, pair, b);
  rec["rows"] = bias_rows(scene, pair, b, RowSource::emulated, scene.distances,
                          search_bias_sampled(source, scene, pair, b, scene.distances), mts);
  return rec;
}

void run_bias(const BiasCliOptions& o, const GlobalOptions& g) {
  check_output_spares_inputs("-o", o.out.output, {{"the scene file", o.scene.scene_file}});
  const BiasOptions b = bias_options_of(o);
  const bool rendered = parse_row_source(o.source) == RowSource::rendered;
  // Rendered probes take the driver's own implementation forms, whatever profile was named.
  const Scene scene = rendered ? rendered_counterpart(o.scene.load()) : o.scene.load();
  check_planes_cover_kernel(scene);
  check_tilt(scene, b.tilt_deg);
  note_clamp_without_effect(scene, b);
  nlohmann::json rules = nlohmann::json::object();
  for (const EvalPair& pair : scene.evaluate)  // every format's rule before any work
    if (bias_not_applicable(scene, pair).empty())
      rules[pair.format] = bias_rule(b, scene.storage_format(pair)).r_text;
  std::unique_ptr<GlContext> gl;
  nlohmann::json depth_buffers;
  if (rendered) {
    check_rendered_options(o);
    gl = std::make_unique<GlContext>(GlDeviceChoice::parse(o.gl_device));
    for (const auto& [format, given] : check_scene_renders(scene)) depth_buffers[format] = given;
  }
  check_writable(o.out.output);
  run_record_batch(
      "bias", o.out, o.batch, g,
      [&](OpenClRuntime& rt, nlohmann::json& header) {
        header["source"] = o.source;
        if (gl) {
          header["renderer"] = gl->renderer();
          header["gl_version"] = gl->version();
          header["depth_buffers"] = depth_buffers;
          header.erase("r");
        }
        header["scene"] = scene.json;
        header["scene_name"] = scene.name;
        header["api"] = to_string(b.api);
        if (!gl) header["r"] = rules;  // rendered: the driver's
        if (b.api == BiasApi::vulkan) header["vulkan_representation"] = to_string(b.representation);
        header["slope"] = to_string(b.slope);
        header["clamp"] = b.clamp;
        header["compare"] = b.or_equal ? "or_equal" : "strict";
        header["tilt_deg"] = b.tilt_deg;
        header["viewport"] = {scene.viewport_w, scene.viewport_h};
        header["set_factor"] = b.set_factor;
        return pair_units(scene, [&rt, &gl, &scene, &b](const EvalPair& pair) {
          return bias_record(rt, gl.get(), scene, pair, b);
        });
      },
      render_bias_output);
}

}  // namespace

namespace {

struct BiasTable {
  Cells cells;
  std::vector<std::string> skipped;  // the pairs the bias does not apply to
  bool no_slope = false;             // the caption then says why a factor had nothing to scale
};

std::string bias_number(const nlohmann::json& r, const char* k, const std::string& format) {
  return r.contains(k) && !r.at(k).is_null() ? number_cell(number_from_json(r.at(k), k), format)
         : format == "csv"                   ? ""
                                             : "-";
}

// Text and Markdown put a search's verdict where its number would be; CSV keeps numbers in the
// number columns and the verdicts in columns of their own.
std::string bias_value_or_verdict(const nlohmann::json& r, const char* value, const char* verdict,
                                  const std::string& format) {
  const std::string v = r.value(verdict, std::string("resolved"));
  return format == "csv" || v == "resolved" ? bias_number(r, value, format) : v;
}

std::vector<std::string> bias_row(const nlohmann::json& r, const std::string& format) {
  std::vector<std::string> row = {r.at("technique").get<std::string>(),
                                  r.at("format").get<std::string>(),
                                  r.at("depth_range").get<std::string>(),
                                  bias_number(r, "z", format),
                                  bias_value_or_verdict(r, "units", "verdict", format),
                                  bias_number(r, "units_bound", format),
                                  bias_value_or_verdict(r, "factor", "factor_verdict", format),
                                  bias_number(r, "set_factor", format),
                                  bias_value_or_verdict(r, "set_units", "set_verdict", format),
                                  bias_number(r, "offset", format),
                                  bias_number(r, "eye_separation", format),
                                  bias_number(r, "mts", format)};
  if (format == "csv")
    for (const char* k : {"verdict", "factor_verdict", "set_verdict"})
      row.push_back(r.contains(k) ? r.at(k).get<std::string>() : "");
  return row;
}

BiasTable bias_table(const std::vector<nlohmann::json>& records, const std::string& format) {
  BiasTable t;
  for (const auto& rec : records) {
    if (!rec.value("applicable", true)) {
      t.skipped.push_back(pair_label(rec));
      continue;
    }
    for (const auto& r : rec.at("rows")) {
      t.no_slope = t.no_slope || r.value("factor_verdict", std::string()) == kNoSlope;
      t.cells.push_back(bias_row(r, format));
    }
  }
  return t;
}

// r per format as the header records it; rendered runs have none: the driver's.
std::string bias_r_text(const nlohmann::json& header) {
  if (!header.contains("r")) return "the driver's";
  std::vector<std::string> parts;
  for (const auto& [format, rule] : header.at("r").items())
    parts.push_back(fmt::format("{} for {}", rule.get<std::string>(), format));
  std::string r_text = fmt::format("{}", fmt::join(parts, ", "));
  if (r_text.find("(e") != std::string::npos)
    r_text += ", e the exponent of the primitive's largest depth";
  return r_text;
}

const char* bias_setting_names(const std::string& api) {
  return api == "d3d"      ? "DepthBias / SlopeScaledDepthBias"
         : api == "vulkan" ? "depthBiasConstantFactor / depthBiasSlopeFactor"
                           : "glPolygonOffset(factor, units)";
}

std::string no_slope_note(const nlohmann::json& header) {
  return fmt::format(
      " {}: the planes' slope is all but 0 in some frame{}, so no slope "
      "factor up to 2^24 moves the overlay as far as the units do: the "
      "factor has nothing to scale.",
      kNoSlope,
      header.value("tilt_deg", 0.0) > 0 ? ""
                                        : " (at tilt 0 they face the camera, but for the scene's "
                                          "small rotation; --tilt gives them a slope)");
}

std::string bias_caption(const nlohmann::json& header, const BiasTable& t) {
  const std::string api = header.value("api", std::string("gl"));
  const auto viewport = header.value("viewport", std::vector<int>{0, 0});
  const std::string r_text = bias_r_text(header);
  return fmt::format(
      "Smallest depth bias for a coplanar overlay (scene {}, {}, {} slope, compare {}{}): "
      "plane B lies in plane A, tessellated along the other diagonal, and is drawn after it with "
      "the bias; it must pass the depth test at every kernel pixel of every frame. units: the "
      "constant term alone (factor 0); factor: the slope term alone (units 0), for depth slopes "
      "per pixel of the scene's {}x{} viewport (a taller viewport at the same field of view has "
      "flatter slopes per pixel and needs a larger factor); set units: the "
      "units needed beside the set factor -- the pair to give {}. Values are signed as you set "
      "them (negative: toward the camera under LESS). offset: the constant bias in window depth "
      "(units x r{}; r = {}); eye separation: how "
      "far it moves a fragment toward the camera at z, beside the MTS (the separation two planes "
      "need without bias, at the scene's orientations: --tilt does not enter it).{}{}",
      header.value("scene_name", std::string("?")),
      header.value("source", std::string("emulated")) == "rendered"
          ? fmt::format("rendered on {}", header.value("renderer", std::string("?")))
          : api + " rules",
      header.value("slope", std::string("max")),
      header.value("compare", std::string("strict")) == "strict" ? "LESS/GREATER" : "LEQUAL/GEQUAL",
      header.value("tilt_deg", 0.0) > 0
          ? fmt::format(", planes tilted {} degrees", human(header.value("tilt_deg", 0.0)))
          : "",
      viewport.at(0), viewport.at(1), bias_setting_names(api),
      header.value("clamp", 0.0) != 0
          ? fmt::format(", after the API's clamp {}, which limits {} offsets only",
                        human(header.value("clamp", 0.0)),
                        header.value("clamp", 0.0) > 0 ? "positive" : "negative")
          : "",
      r_text, t.no_slope ? no_slope_note(header) : "",
      t.skipped.empty() ? ""
                        : fmt::format(" Not applicable (the fragment stage writes depth, which "
                                      "replaces the offset depth): {}.",
                                      fmt::join(t.skipped, ", ")));
}

std::vector<Column> bias_columns(bool csv) {
  std::vector<Column> cols = {
      {"technique", true}, {"format", true}, {"depth_range", true}, {"z"},         {"units"},
      {"units (bound)"},   {"factor"},       {"set factor"},        {"set units"}, {"offset"},
      {"eye separation"},  {"MTS"}};
  if (csv)
    for (const char* c : {"units verdict", "factor verdict", "set verdict"})
      cols.push_back({c, true});
  return cols;
}

}  // namespace

std::string render_bias_output(const nlohmann::json& header,
                               const std::vector<nlohmann::json>& records,
                               const OutputOptions& out) {
  if (out.format_out == "json") return records_json(header, records, !out.no_timing);
  const BiasTable t = bias_table(records, out.format_out);
  const std::string caption = bias_caption(header, t);
  return captioned(caption, bias_columns(out.format_out == "csv"), t.cells, out.format_out);
}

void add_bias_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<BiasCliOptions>();
  auto* cmd = app.add_subcommand(
      "bias",
      "Depth bias (polygon offset) for coplanar geometry: per pair and distance, the smallest\n"
      "bias that lets an overlay lying in a surface (a decal, a second mesh of the same surface,\n"
      "tessellated its own way) pass the depth test at every pixel of every frame, on the\n"
      "emulated pipeline, with the bias applied as the API specifies (--api). Reports the\n"
      "constant term alone (units), the slope term alone (factor), the units needed beside a\n"
      "slope factor (--set-factor, the pair to set), and what the constant bias means in eye\n"
      "space next to the MTS. docs/bias.md says how to read it.\n"
      "Examples:\n"
      "  depthprec bias -t reversed -f float32 --distances 10,100,1000,5000\n"
      "  depthprec bias -t standard -f unorm24,unorm16 --api d3d --tilt 45\n"
      "  depthprec bias --api vulkan --vulkan-representation force_unorm -f float32");
  o->scene.add_to(*cmd, true);
  cmd->add_option("--api", o->api,
                  "Whose bias rules: gl (glPolygonOffset), d3d (DepthBias, SlopeScaledDepthBias), "
                  "vulkan (depthBias*Factor)")
      ->capture_default_str();
  cmd->add_option("--r-unorm", o->r_unorm,
                  "r of unorm buffers where the API leaves it open: pow2 (2^-n), step "
                  "(1/(2^n-1)), double_step (2/(2^n-1), Mesa's Gallium drivers, llvmpipe), "
                  "double_pow2 (2^(1-n)) (default: step for gl and d3d, pow2 for vulkan)");
  cmd->add_option("--vulkan-representation", o->representation,
                  "Vulkan's depthBiasRepresentation: format, force_unorm (float buffers as 24-bit "
                  "unorm), float (r = 1)")
      ->capture_default_str();
  cmd->add_option("--slope", o->slope,
                  "The slope m: max (max(|dz/dx|, |dz/dy|)) or sqrt (sqrt(dz/dx^2 + dz/dy^2); not "
                  "d3d)")
      ->capture_default_str();
  cmd->add_option("--clamp", o->clamp,
                  "The APIs' signed clamp (DepthBiasClamp, depthBiasClamp, glPolygonOffsetClamp): "
                  "> 0 limits the offset from above (min(offset, clamp)), < 0 from below "
                  "(max(offset, clamp)), 0 none. Under LESS the bias is negative, so only a "
                  "negative clamp limits it; under GREATER a positive one")
      ->capture_default_str();
  cmd->add_option("--tilt", o->tilt,
                  "Tilt both planes this many degrees about the view's x axis, on top of the "
                  "scene's rotation: the slope term's case. Up to 82.4 in the default scene (the "
                  "view's lower edge must still meet the planes; the limit is named when passed)")
      ->capture_default_str();
  cmd->add_option("--set-factor", o->set_factor,
                  "The slope factor of the pair to set (its sign follows the compare; 0: leave "
                  "that search out)")
      ->capture_default_str();
  cmd->add_flag("--or-equal", o->or_equal,
                "Compare with LEQUAL/GEQUAL instead of the APIs' default LESS/GREATER");
  cmd->add_option("--source", o->source,
                  "emulated (the emulated pipeline with the API's rules) or rendered (every "
                  "probe drawn with glPolygonOffset through the system's OpenGL: the driver's r "
                  "and arithmetic; no MTS column)")
      ->capture_default_str()
      ->check(CLI::IsMember({"emulated", "rendered"}));
  add_gl_device_option(cmd, o->gl_device);
  o->out.add_to(*cmd);
  o->batch.add_to(*cmd, "pairs (k in scene order)");
  cmd->callback([o, &global]() { run_bias(*o, global); });
}

}  // namespace depthprec::cli
