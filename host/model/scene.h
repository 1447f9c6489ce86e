// A scene: every parameter of the MTS measurement (docs/spec.md 5.1), the pipeline options
// (docs/spec.md 2) and the (technique, format[, depth_range]) pairs to evaluate.
// data/gilg2021.json, embedded in the binary, is the one source of the defaults: a scene file or a
// --set override only says what differs from it.
#pragma once

#include <algorithm>
#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "host/model/storage_format.h"
#include "host/model/technique.h"

namespace depthprec {

enum class MatrixPrecision { single, binary64 };  // "float", "double"
enum class Compose { separate, premultiplied };
enum class Divide { reciprocal, exact };
// How the interpolated depth (or 1/w) plane of a triangle is set up and evaluated
// (docs/spec.md 2.4): vertex: anchored at its first vertex, gradients divided by the area, each
// pixel (c0 + dzdx (px - x0)) + dzdy (py - y0); origin_fma: as Mesa's llvmpipe does (22.3,
// lp_state_setup.c): gradients as differences times 1/area, the value a0 referred to the
// framebuffer origin, each pixel fma(dzdy, y, fma(dzdx, x, a0)) at integer pixel coordinates,
// the vertices reordered (v1, v0, v2) when the triangle's area is negative; origin_quads: as
// Mesa's softpipe does (sp_setup.c, sp_quad_depth_test.c): anchored at the vertex of least y,
// gradients times 1/area, a0 at the origin, evaluated per 2x2 quad of pixels from its even
// corner by increments, z0 = (a0 + dzdx qx) + dzdy qy, z0 + dzdx, z0 + dzdy, (z0 + dzdx) + dzdy.
enum class PlaneForm { vertex, origin_fma, origin_quads };
// The viewport transform: separate multiply and add, or fused (fma(ndc, scale, translate), as
// llvmpipe's generated vertex code does on an FMA CPU).
enum class ViewportForm { separate, fma };
// The vertex stage's matrix-vector products, row by row: separate multiplies and adds in the
// order ((m0 x + m1 y) + m2 z) + m3 w, or fused as llvmpipe's compiled vertex shader fuses
// depthprec's (host/model/vertex_stage.h; measured pixel by pixel, docs/validation.md).
enum class VertexForm { separate, fma };
// The shaders' natural log (log_vertex, log_fragment): the library's (OpenCL's log, <= 3 ulp), or
// llvmpipe's approximation (interface/llvmpipe_log.h).
enum class LogForm { library, llvmpipe };
// Triangles that cross the viewport edge: rasterised as they are, their fragments outside the
// viewport never seen (none), or clipped into a fan of new triangles as llvmpipe's clip stage
// does (Mesa 22.3 draw_pipe_clip.c), whose new vertices carry other roundings.
enum class ClipForm { none, llvmpipe };
// How the vertex stage reaches eye space when the scene sits at world_position (docs/spec.md 2,
// "World position"): absolute: the planes' model matrices carry the world translation and the
// view matrix the camera's, as matrix_precision and compose say; camera_relative: the model-view's
// translation formed in binary64 (model minus camera) before the matrix goes to the GPU;
// relative_to_eye: Cesium's split of binary64 world positions into binary32 high and low parts
// (interface/relative_to_eye.h), subtracted from the eye's on the GPU.
enum class Transform { absolute, camera_relative, relative_to_eye };
// The vertex shader's precision (GLSL ES): highp, binary32; mediump, binary16 (relative precision
// 2^-10, interface/binary16.h), as mobile GPUs run a shader that declares it.
// The shaders' precision (interface/binary16.h dp_shader_round's numbers): binary32, GLSL ES
// mediump (binary16), or the GLSL ES 1.00 highp minimum (17 bits).
enum class ShaderPrecision { highp = 0, mediump = 1, es2_highp = 2 };
const char* to_string(ShaderPrecision p);  // "highp", "mediump", "es2_highp"
ShaderPrecision parse_shader_precision(const std::string& s);
// The bound on world_position's coordinates, 2^40: relative to eye keeps a coordinate's high part
// (a multiple of 65536) exact in binary32 below it.
constexpr double kMaxWorldCoordinate = 1099511627776.0;
const char* to_string(Transform t);  // "absolute", "camera_relative", "relative_to_eye"
Transform parse_transform(const std::string& s);  // throws InputError listing the names

struct Pipeline {
  // The depth range of pairs that name none; none here ("technique" in a scene): each technique's
  // own (TechniqueInfo::range: zero_to_one for the reversed mappings, gl otherwise).
  std::optional<DepthRange> depth_range;
  MatrixPrecision matrix_precision = MatrixPrecision::single;
  Compose compose = Compose::separate;
  Divide divide = Divide::reciprocal;
  Rounding rounding = Rounding::nearest_even;
  Denormals denormals = Denormals::keep;
  bool contraction = false;
  PlaneForm plane = PlaneForm::vertex;
  ViewportForm viewport = ViewportForm::separate;
  VertexForm vertex = VertexForm::separate;
  LogForm log = LogForm::library;
  ClipForm clip = ClipForm::none;
  // Sub-pixel snapping (interface/snap.h): window x and y rounded to 2^-snap_bits pixel before
  // coverage and the depth plane are computed from them; 0: not snapped.
  int snap_bits = 0;
  // Triangle records per grid triangle (interface/mts_layout.h): one, or a clipped fan's slots.
  int clip_slots() const;
  Conversion conversion = Conversion::exact;  // unorm codes: correctly rounded, or llvmpipe's
  Transform transform = Transform::absolute;
  ShaderPrecision shader_precision = ShaderPrecision::highp;
  // An API envelope whose adversary the emulation takes (interface/adversary.h, a bound model with
  // one: d3d11, vulkan_min); empty: none.
  std::string envelope;
};

struct EvalPair {
  Technique technique;
  std::string format;
  DepthRange depth_range;
  std::string label() const;  // "reversed/float32/zero_to_one"
  // technique, format and depth_range, as every JSON record of a pair carries them.
  nlohmann::json fields() const;
};

// The label of a JSON record that carries a pair's fields: "reversed/float32/zero_to_one".
std::string pair_label(const nlohmann::json& record);

// Rotation angles (radians) about x, y and z of a plane's frame: R = Rx Ry Rz (docs/spec.md 5.1).
using Angles = std::array<double, 3>;

// How an MTS is sampled over orientations (docs/mts.md, "The worst case"): the paper's frames
// alone, or the worst case over the rotation cube the paper's path samples.
enum class Sampling { paper, worst_case };
const char* to_string(Sampling s);  // "paper", "worst_case"

// When worst_case sampling stops refining a row (docs/mts.md, "The worst case").
struct WorstCaseSettings {
  int min_rounds = 0;    // rounds every resolved row runs, whatever they find
  int max_rounds = 0;    // rounds after the paper's frames, at most
  int round_size = 0;    // orientations per round
  double tolerance = 0;  // a refinement that raises the MTS by at most this (relative) ends it
};

struct Scene {
  std::string name;
  std::string description;
  std::string source;  // file path, or "embedded:data/gilg2021.json"
  double near = 0, far = 0;
  int kernel_w = 0, kernel_h = 0, viewport_w = 0, viewport_h = 0;
  double fov_y_deg = 0;
  double plane_margin = 0;
  int plane_subdivisions = 0;
  int frames = 0;
  double delta_a = 0;
  double rotation_range_deg = 0;
  std::array<double, 3> rotation_step{}, rotation_offset{};
  std::vector<double> distances;  // in the order given (rows are searched and journaled so)
  // The distances nearest first: the rows of a table by z.
  std::vector<double> distances_ascending() const {
    std::vector<double> d = distances;
    std::sort(d.begin(), d.end());
    return d;
  }
  // Where the camera and the planes sit in the world (binary64): the camera still looks down its
  // -z axis at the planes z away; pipeline.transform says how the GPU gets there.
  std::array<double, 3> world_position{};
  bool at_world_origin() const {
    return world_position[0] == 0 && world_position[1] == 0 && world_position[2] == 0;
  }
  double rel_precision = 0;
  double max_separation_factor = 0;
  int stiffness_probes = 0;  // per side of each resolved MTS (docs/stability.md)
  Sampling sampling = Sampling::worst_case;
  // The guaranteed MTS's bound model (host/model/bound_model.h): binary32, a profile's own, or
  // an API's envelope.
  std::string bound_model = "binary32";
  // The relative error depth interpolation may make (of the interpolated depth, or 1/w), for the
  // bound and an envelope's adversary: the model's own where unset (vulkan_min: 10^-5, the
  // others 0). Vulkan leaves it loosely stated; a user who measured a device sets it.
  std::optional<double> interpolation_tolerance;
  double interpolation_tolerance_or(double model_value) const {
    return interpolation_tolerance.value_or(model_value);
  }
  WorstCaseSettings worst_case;
  Pipeline pipeline;
  TechniqueParams params;
  std::vector<EvalPair> evaluate;

  nlohmann::json json;  // the merged, validated scene as JSON (for output headers)

  // The depth range a pair of technique t gets when it names none.
  DepthRange range_for(Technique t) const { return pipeline.depth_range.value_or(info(t).range); }

  StorageFormat storage_format(const EvalPair& p) const {
    return StorageFormat::parse(
        p.format, pipeline.rounding, pipeline.denormals,
        p.format.rfind("unorm", 0) == 0 ? pipeline.conversion : Conversion::exact);
  }
};

// path empty: the embedded default. overrides: "key=value" with a JSON value (bare words are
// taken as strings), dotted keys for nested objects: "pipeline.depth_range=zero_to_one",
// "kernel=[50,50]", "near=0.1". Throws InputError naming the file, line:column and key.
// check = false leaves check_pairs to a caller that replaces the pairs first. origins names the
// option behind an override's key ("near" -> "--near 5"), so errors blame what the user typed;
// an override it does not name is blamed on "--set key=value".
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {},
                 bool check = true, const std::map<std::string, std::string>& origins = {});

// The name of a scene changed on the command line (--set, a named option, other pairs): "+set"
// appended, once, so an output never labels it with the name of the scene it started from.
std::string changed_scene_name(const std::string& name);

// The same from the text of a scene file (path names it in errors; "" for no file).
Scene load_scene_text(const std::string& text, const std::string& path,
                      const std::vector<std::string>& overrides = {}, bool check = true,
                      const std::map<std::string, std::string>& origins = {});

// Checks what the scene's pairs need of it (a finite far plane for the techniques that clip at
// one); throws InputError naming the pair. load_scene calls it; so does whoever replaces the pairs.
void check_pairs(const Scene& scene);

// Refuses a kernel wider than the planes (every probe would see uncovered pixels and none could
// be accepted). The commands call it up front; the library leaves such scenes to the search,
// which never accepts a probe with an uncovered pixel (tests use them to check exactly that).
void check_planes_cover_kernel(const Scene& scene);

// A scene from a JSON object (as JSON outputs carry it in their header), over the defaults.
Scene scene_from_json(const nlohmann::json& j, const std::string& source);

// The JSON text of the embedded default scene.
const std::string& default_scene_text();

// The merged JSON of a scene (the embedded defaults, the file, --set and the profile, merged by
// load_scene_text) read into a Scene, every field typed and checked (host/model/scene_parse.cpp).
// where_name and text: the file an error points into (at the key's line where text is given);
// origins: the command-line option that set a key, blamed instead of the file.
Scene parse_scene(const nlohmann::json& merged, const std::string& source,
                  const std::string& where_name, const std::string& text,
                  const std::map<std::string, std::string>& origins);

}  // namespace depthprec
