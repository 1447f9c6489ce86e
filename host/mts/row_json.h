// MTS rows to and from JSON: the JSON output's rows, the journal of a batch run (one row per
// line), and the shards `depthprec merge` joins all use this one form. Doubles round-trip
// exactly; non-finite values are the strings "inf" / "-inf".
#pragma once

#include <nlohmann/json.hpp>

#include "host/mts/mts_row.h"

namespace depthprec {

nlohmann::json row_to_json(const MtsRow& r, bool timing);
MtsRow row_from_json(const nlohmann::json& j);  // throws InputError naming the bad field

// "technique/format/range@z": identifies a row across runs, journals and shards.
std::string row_key(const EvalPair& pair, double z);

}  // namespace depthprec
