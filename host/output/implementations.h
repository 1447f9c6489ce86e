// The implementations depthprec emulates and bounds, listed: every profile (host/model/profile.cpp)
// and every bound model, the API envelopes among them (host/model/bound_model.cpp), with what
// each is and where its tolerances come from. `depthprec pipelines --list` prints it and the
// report shows it, from this one list.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace depthprec {

struct Implementation {
  std::string name;
  std::string kind;    // "profile", "bound model", or "profile and bound model"
  std::string what;    // the profile's line, else the model's
  std::string source;  // the model's sources; a profile alone: the settings it makes
};

std::vector<Implementation> implementations();

// The list in a command's formats: text, Markdown, CSV or JSON (an array of objects).
std::string implementations_output(const std::string& format);
nlohmann::json implementations_json();

}  // namespace depthprec
