// A scene's merged JSON (host/model/scene.cpp: the embedded defaults, the file, --set and the
// profile) read into a Scene: every field typed and checked, with errors that blame the file or
// the option that set it.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "host/model/scene.h"

namespace depthprec {

// where_name and text: the file an error points into (at the key's line where text is given);
// origins: the command-line option that set a key, blamed instead of the file.
Scene parse_scene(const nlohmann::json& merged, const std::string& source,
                  const std::string& where_name, const std::string& text,
                  const std::map<std::string, std::string>& origins);

}  // namespace depthprec
