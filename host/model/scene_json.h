// A scene file's JSON as the user wrote it: parsed with every key given twice refused, and each
// error placed at its file, line and column (host/model/scene.cpp reads the values).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace depthprec {

// The JSON of a scene file's text (source names it in errors); throws InputError at the position
// of malformed JSON or of a key given twice in one object.
nlohmann::json parse_scene_json(const std::string& text, const std::string& source);

// "source:line:column" of the first occurrence of "key" in text, or source alone when the text is
// not at hand (a --set override, an output's header).
std::string scene_key_where(const std::string& source, const std::string& text,
                            const std::string& key);

}  // namespace depthprec
