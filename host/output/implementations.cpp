#include "host/output/implementations.h"

#include <fmt/format.h>

#include "host/model/bound_model.h"
#include "host/model/profile.h"
#include "host/output/text_table.h"

namespace depthprec {

std::vector<Implementation> implementations() {
  std::vector<Implementation> out;
  for (const Profile& p : profiles()) {
    Implementation i{p.name, "profile", p.what, fmt::format("{}", fmt::join(p.sets, ", "))};
    for (const BoundModel& m : bound_models())
      if (i.name == m.name) {
        i.kind = "profile and bound model";
        i.source = m.source;
      }
    out.push_back(i);
  }
  for (const BoundModel& m : bound_models()) {
    bool listed = false;
    for (const Implementation& i : out) listed = listed || i.name == m.name;
    if (!listed) out.push_back({m.name, "bound model", m.what, m.source});
  }
  return out;
}

nlohmann::json implementations_json() {
  nlohmann::json list = nlohmann::json::array();
  for (const Implementation& i : implementations())
    list.push_back({{"name", i.name}, {"kind", i.kind}, {"what", i.what}, {"source", i.source}});
  return list;
}

std::string implementations_output(const std::string& format) {
  if (format == "json") return implementations_json().dump(2) + "\n";
  if (format == "text") {  // a list: the sentences are too long for a table's columns
    std::string out =
        "The implementations depthprec emulates (--profile NAME) and the models its guaranteed "
        "MTS holds for (--set bound_model=NAME), the API envelopes among them (docs/spec.md 2, "
        "\"Envelopes\"):\n";
    for (const Implementation& i : implementations())
      out += fmt::format("\n{} ({}): {}\n    {}\n", i.name, i.kind, i.what, i.source);
    return out;
  }
  Cells cells;
  for (const Implementation& i : implementations())
    cells.push_back({i.name, i.kind, i.what, i.source});
  return captioned(
      "The implementations depthprec emulates (--profile NAME) and the models its guaranteed MTS "
      "holds for (--set bound_model=NAME), the API envelopes among them (docs/spec.md 2, "
      "\"Envelopes\"; docs/bound.md)",
      {{"name", true}, {"kind", true}, {"what", true}, {"source", true}}, cells, format);
}

}  // namespace depthprec
