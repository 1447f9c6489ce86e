#include "host/model/scene_json.h"

#include <fmt/format.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "host/base/errors.h"

namespace depthprec {

using nlohmann::json;

namespace {

// "line L, column C" of a byte offset in text (1-based, as editors count).
std::string position_of(const std::string& text, size_t offset) {
  size_t line = 1, col = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return fmt::format("{}:{}", line, col);
}

// Where a key first appears in the file, for errors about keys (nlohmann keeps no positions).
}  // namespace

std::string scene_key_where(const std::string& source, const std::string& text,
                            const std::string& key) {
  const size_t at = text.empty() ? std::string::npos : text.find("\"" + key + "\"");
  if (at == std::string::npos) return source;
  return source + ":" + position_of(text, at);
}

namespace {

// Where the n-th (from 0) occurrence of "key" as a key stands in text ("" when not found: a key
// written with escapes).
std::string key_position(const std::string& text, const std::string& key, size_t n) {
  const std::string quoted = "\"" + key + "\"";
  for (size_t at = text.find(quoted); at != std::string::npos; at = text.find(quoted, at + 1)) {
    const size_t colon = text.find_first_not_of(" \t\r\n", at + quoted.size());
    if (colon == std::string::npos || text[colon] != ':') continue;
    if (n-- == 0) return position_of(text, at);
  }
  return "";
}

// JSON allows a key twice in an object and nlohmann keeps the last: a scene that sets `near`
// twice would run with one of them unsaid. The parser's callback sees every key in order, so a
// repeat is refused with its path and both places.
class DuplicateKeyCheck {
 public:
  DuplicateKeyCheck(const std::string& text, const std::string& source)
      : text_(text), source_(source) {}

  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        frames_.push_back(Frame{false, 0, {}, {}, {}});
        break;
      case json::parse_event_t::array_start:
        frames_.push_back(Frame{true, 0, {}, {}, {}});
        break;
      case json::parse_event_t::key: {
        const std::string key = parsed.get<std::string>();
        const size_t nth = seen_[key]++;
        Frame& f = frames_.back();
        f.key = key;
        if (!f.keys.insert(key).second) {
          const std::string at = key_position(text_, key, nth);
          throw InputError(
              fmt::format("{}{}: key '{}' given twice{}; JSON keeps only one of them: give it once",
                          source_, at.empty() ? "" : ":" + at, path(), first_place(key, f)));
        }
        f.first[key] = nth;
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        next_element();
        break;
      case json::parse_event_t::value:
        next_element();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool array = false;
    size_t index = 0;                       // arrays: the element being read
    std::string key;                        // objects: the key being read
    std::set<std::string> keys;             // objects: the keys read so far
    std::map<std::string, size_t> first{};  // objects: which occurrence of each key it was
  };
  void next_element() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  std::string path() const {
    std::string p;
    for (const Frame& f : frames_)
      p += f.array ? fmt::format("[{}]", f.index) : (p.empty() ? "" : ".") + f.key;
    return p;
  }
  std::string first_place(const std::string& key, const Frame& f) const {
    const std::string at = key_position(text_, key, f.first.at(key));
    return at.empty() ? "" : fmt::format(" (first at {})", at);
  }
  const std::string& text_;
  const std::string& source_;
  std::vector<Frame> frames_;
  std::map<std::string, size_t> seen_;  // occurrences of each key in the text so far
};

}  // namespace

json parse_scene_json(const std::string& text, const std::string& source) {
  try {
    return json::parse(text, DuplicateKeyCheck(text, source));
  } catch (const json::parse_error& e) {
    std::string msg = e.what();
    const auto p = msg.find("parse error");
    if (p != std::string::npos) msg = msg.substr(p);
    throw InputError(fmt::format("{}:{}: malformed JSON: {}", source,
                                 position_of(text, e.byte > 0 ? e.byte - 1 : 0), msg));
  } catch (const json::exception& e) {
    // e.g. a number too large for binary64 (found by the fuzzer): no position is known
    std::string msg = e.what();
    const auto p = msg.find("] ");
    if (p != std::string::npos) msg = msg.substr(p + 2);
    throw InputError(fmt::format("{}: malformed JSON: {}", source, msg));
  }
}

}  // namespace depthprec
