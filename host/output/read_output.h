// A command's JSON output read back by another command: `report --from`, `plot`, `compare
// --emulated/--rendered`. What they draw or pair must be a whole run's rows: one shard would pass
// for the whole ("distances 3" with one row shown), and another command's records are no rows.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace depthprec {

// The JSON object in path. who: the command reading it, for errors ("report", "plot"); role:
// what the file is to it ("--from file"). Throws InputError for a directory, an unreadable file
// or one that is not a JSON object.
nlohmann::json read_json_output(const std::string& path, const std::string& who,
                                const std::string& role);

// Throws InputError when doc is one shard of a batch run with --shard i/N (N > 1), saying to
// merge the shards first.
void refuse_shard(const nlohmann::json& doc, const std::string& path, const std::string& who);

// Throws InputError unless doc holds the MTS rows of a whole run (mts, table, render or merge),
// naming what it is otherwise: a --profiles output, another command's records, a shard.
// otherwise: what who does with a --profiles output, for its message.
void check_rows_output(const nlohmann::json& doc, const std::string& path, const std::string& who,
                       const std::string& profiles_hint);

}  // namespace depthprec
