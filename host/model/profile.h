// Implementation profiles: named bundles of the pipeline's implementation choices
// (docs/spec.md 2), so a user can ask "what would this rasterizer give?" with one option. A
// profile is a list of scene settings, applied as --set would apply them.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace depthprec {

struct Profile {
  const char* name;
  const char* what;               // one line for --help and docs
  std::vector<std::string> sets;  // "pipeline.plane=origin_fma", ...
  const char* bias_unorm_r;       // `bias`'s r for unorm buffers (--r-unorm); null: not modelled
};

// A profile's setting "pipeline.plane=origin_fma" as ("plane", "origin_fma"), its value as the
// scene's JSON holds it: a whole number ("pipeline.snap=8") as a number, anything else a string.
std::pair<std::string, nlohmann::json> pipeline_setting(const std::string& set);

const std::vector<Profile>& profiles();
// Throws InputError listing the profiles.
const Profile& profile(const std::string& name);
std::string profile_names();  // "ideal, llvmpipe, softpipe"

}  // namespace depthprec
