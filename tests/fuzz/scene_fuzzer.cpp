// libFuzzer target: the scene parser and validator (host/model/scene.cpp) on arbitrary bytes. Bad
// input must end in depthprec::InputError with a message; anything else (a crash, a sanitizer
// report, another exception) is a bug. Built and run by scripts/fuzz.sh; see docs/fuzzing.md.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "host/base/errors.h"
#include "host/model/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const depthprec::Scene s = depthprec::load_scene_text(text, "fuzz.json");
    // a scene that passes validation must be usable: every pair's format parses again
    for (const auto& p : s.evaluate) (void)s.storage_format(p);
  } catch (const depthprec::InputError& e) {
    if (std::string(e.what()).empty()) std::abort();  // errors must say something
  }
  return 0;
}
