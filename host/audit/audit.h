// The scene audit (docs/audit.md): per set-up, the pixels of a user's scene where the stored depth
// lets the wrong surface win, grouped into the pairs of surfaces that fight, each with the
// separation along the view ray, the MTS the set-up needs there, and its cheapest fixes.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "host/audit/audit_reference.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

// Pixels of one view (an index into AuditRequest::frames).
struct PixelSample {
  int frame = 0;
  std::vector<std::pair<int, int>> pixels;
};

// One pair of surfaces (draws) that fight: the one the depth test kept (winner) where the other
// (front) is nearer.
struct FightPair {
  int winner_draw = 0, front_draw = 0;                    // indices into SceneGeometry::draws
  uint32_t winner_triangle = 0, front_triangle = 0;       // scene-wide, at the first pixel found
  uint64_t pixels = 0;                                    // over every frame
  double depth_min = 0, depth_median = 0, depth_max = 0;  // the front surface's eye depth, m
  double separation_min = 0, separation_median = 0;       // winner's minus front's, along the ray
  // Per view it fights in, up to kFixPixels of its pixels (x, y): every fix is checked on each.
  std::vector<PixelSample> samples;
  std::vector<uint32_t> triangles;  // the triangles fighting at the sampled pixels
  // The fixes (audit_fixes.h): NaN / empty / nullopt where none was found or asked for.
  double mts = NAN;        // the set-up's MTS at depth_median (the scene's measurement)
  double mts_bound = NAN;  // and its guaranteed MTS there (host/mts/mts_bound.h)
  // Move the front surface this much nearer: mts_bound (mts where the model has no bound) less
  // separation_min.
  double offset = NAN;
  std::optional<double> near_plane;    // the nearest near plane that resolves the sample
  std::vector<std::string> resolving;  // other set-ups that resolve the sample
  std::optional<double> bias_units;    // constant depth bias on the front surface (API units)
  std::string bias_note;               // why no bias is given
};

struct SetupAudit {
  EvalPair pair;
  uint64_t frames = 0, pixels = 0, covered_pixels = 0, fighting_pixels = 0, coplanar_pixels = 0,
           discarded_pixels = 0;
  // covered but nothing drawn (every fragment at the cleared value); a surface's own seams
  uint64_t undrawn_pixels = 0, seam_pixels = 0;
  // won by the front surface, but within what another conformant implementation may store
  // (AUDIT_AT_RISK): fights on some implementation or view
  uint64_t at_risk_pixels = 0;
  // Under shaders below binary32 (pipeline.shader_precision mediump or es2_highp): its name (empty
  // under highp), and the fighting pixels the same views with highp shaders do not fight at (the
  // fights the device's precision alone makes).
  std::string reduced_precision;
  uint64_t precision_only_pixels = 0;
  double fix_seconds = 0;
  uint64_t records = 0, culled = 0, clipped = 0, non_finite = 0;  // frame 0's triangles
  std::vector<FightPair> pairs;                                   // by pixels, most first
  std::vector<FightPair> coplanar_pairs;  // surfaces in one plane where the later one lost
  AuditPixels image;                      // frame 0's pixels
  std::vector<uint8_t> shade;  // frame 0: per pixel how squarely its front surface faces the eye
  double setup_seconds = 0, pixel_seconds = 0;
};

constexpr size_t kFixPixels = 64;

struct AuditRequest {
  std::vector<AuditCamera> frames;  // frame 0 first: the camera as given, then the jittered ones
  bool reference = false;           // the host reference instead of the device (tests)
  size_t max_pairs = 20;            // pairs reported per set-up (the rest counted in the totals)
};

// runtime may be null when request.reference is set.
SetupAudit audit_setup_pair(OpenClRuntime* runtime, const Scene& scene, const EvalPair& pair,
                            const SceneGeometry& geometry, const AuditRequest& request);

// Frames 1 .. n - 1 of a jittered camera: the eye and target moved together by up to `jitter`
// metres along each axis (a Halton sequence, deterministic).
std::vector<AuditCamera> jittered_frames(const AuditCamera& camera, int frames, double jitter);

}  // namespace depthprec
