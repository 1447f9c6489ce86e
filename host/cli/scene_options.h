// Scene selection and overrides shared by every command that runs a scene: a scene file
// (default: the embedded data/gilg2021.json), --set key=value for any field, and named flags for
// the common ones (each is a --set in disguise, so one code path validates them all).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "host/model/scene.h"

namespace depthprec::cli {

struct SceneOptions {
  std::string scene_file;
  std::vector<std::string> sets;
  std::vector<std::string> techniques, formats, depth_ranges;
  std::string near, far, kernel, frames, rel_precision, matrix_precision, compose, divide, rounding,
      denormals, log_k, fov, profile;
  std::vector<std::string> distances;
  // Settings the command takes from elsewhere where the command line gives none: key=value, and
  // what messages call its origin ("near=0.1", "the file camera's znear (0.1)"), so a note or an
  // error names where the value came from rather than a --set the user never typed.
  std::vector<std::pair<std::string, std::string>> implied;

  void add_to(CLI::App& cmd, bool with_pairs);
  bool any() const;  // whether the command line names a scene or sets anything in one
  // Loads the scene with every override applied; --technique/--format/--depth-range replace the
  // scene's pair list with their cross product.
  Scene load() const;
};

// Options a command's scene options add that it does not use: hidden from its --help, and refused
// when given (a usage error naming them and why), rather than accepted and ignored.
void refuse_unused(CLI::App& cmd, const std::vector<std::string>& names, const std::string& why);

// The output format a file name asks for by its extension (.json, .csv, .md, .txt); "" for none.
std::string format_of_extension(const std::string& path);

struct OutputOptions {
  std::string format_out = "text";
  std::string output;  // file; "" = stdout
  bool no_timing = false;
  void add_to(CLI::App& cmd);
};

// --resume and --shard of the batch commands. units: what the shards split, for --help.
struct BatchOptions {
  bool resume = false;
  std::string shard;
  void add_to(CLI::App& cmd, const std::string& units);
};

}  // namespace depthprec::cli
