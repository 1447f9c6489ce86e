// Where `audit --png` writes, settled and checked before any work: a set-up's pixels take seconds
// to minutes, and a PNG that cannot be written found after them would cost the run and its -o
// report too.
#pragma once

#include <string>
#include <vector>

#include "host/model/scene.h"
#include "host/output/output_guard.h"

namespace depthprec::cli {

// The prefix the PNGs' names start with. --png PREFIX names files PREFIX-<set-up>.png; a PREFIX
// that is a directory (it ends with '/' or exists as one) gets <gltf stem>-<set-up>.png inside
// it. Throws OutputError when the directory the files go in does not exist, is no directory, or
// cannot be written in. "" for no --png.
std::string png_prefix(const std::string& png, const std::string& gltf_file);

// PREFIX-<technique>-<format>-<range><kind>.png; kind "" (the view) or "-margin".
std::string png_name(const std::string& prefix, const EvalPair& pair, const char* kind);

// Every PNG the set-ups will write: none may be a directory or a file the run reads (inputs).
void check_png_names(const std::string& prefix, const std::vector<EvalPair>& pairs,
                     const std::vector<NamedInput>& inputs);

}  // namespace depthprec::cli
