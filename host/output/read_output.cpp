#include "host/output/read_output.h"

#include <fmt/format.h>

#include "host/base/errors.h"
#include "host/base/read_file.h"

namespace depthprec {

nlohmann::json read_json_output(const std::string& path, const std::string& who,
                                const std::string& role) {
  std::string text;
  try {
    text = read_input_file(path, role);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", who, e.what()));
  }
  auto j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw InputError(fmt::format(
        "{}: '{}' is not a JSON output of depthprec (one written with --format-out json)", who,
        path));
  return j;
}

void refuse_shard(const nlohmann::json& doc, const std::string& path, const std::string& who) {
  if (!doc.contains("shard") || !doc["shard"].is_string()) return;
  const std::string shard = doc["shard"].get<std::string>();
  const auto slash = shard.find('/');
  if (slash == std::string::npos || shard.substr(slash + 1) == "1") return;  // 1/1: the whole
  throw InputError(fmt::format(
      "{}: '{}' is shard {} of a batch: alone it would pass for the whole run; join the shards "
      "first with `depthprec merge PART... --format-out json -o whole.json` and give {} that",
      who, path, shard, who));
}

void check_rows_output(const nlohmann::json& doc, const std::string& path, const std::string& who,
                       const std::string& profiles_hint) {
  const std::string kind = doc.value("kind", std::string());
  if (kind == "profiles")
    throw InputError(fmt::format(
        "{}: '{}' is an `mts --profiles` or `table --profiles` output: its MTS are per profile, "
        "side by side, not one run's rows; {}",
        who, path, profiles_hint));
  if (!doc.contains("rows") || !doc.contains("scene"))
    throw InputError(fmt::format(
        "{}: '{}' is {}; {} reads the JSON output of mts, table, render or merge", who, path,
        kind.empty() ? "not a JSON output of mts, table, render or merge"
                     : fmt::format("the output of `{}`", kind),
        who));
  refuse_shard(doc, path, who);
}

}  // namespace depthprec
