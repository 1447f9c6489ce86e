// "Did you mean ...?" for names a user types: the API and vendor aliases engineers use for depth
// formats and buffers, and the closest of a list of names for a typo.
#pragma once

#include <string>
#include <vector>

namespace depthprec {

// The candidate nearest to `typed` by edit distance (case-insensitive), when it is near enough
// to be a typo (at most a third of its letters, and at least one, differ); "" otherwise.
std::string closest_name(const std::string& typed, const std::vector<std::string>& candidates);

// " (did you mean unorm24?)" for a format alias (D24, d32f, UNORM24, D24_UNORM_S8_UINT, ...) or a
// near miss of a format name; "" when nothing fits.
std::string format_suggestion(const std::string& typed);

// The same for technique names: zbuffer -> standard, reverse_z -> reversed, log -> log_vertex, ...
std::string technique_suggestion(const std::string& typed, const std::vector<std::string>& names);

// The same for Lapidous-Jiao buffer names: reversed -> complementary_z, standard -> z, ...
std::string buffer_suggestion(const std::string& typed);

}  // namespace depthprec
