// The guaranteed MTS in the tables (docs/bound.md): each row's mts_bound
// beside its sampled mts, and in the wide table a second grid of the bounds under the first.
#pragma once

#include <string>
#include <vector>

#include "host/model/scene.h"
#include "host/mts/mts_row.h"

namespace depthprec {

// A row's mts_bound: the number ("inf" where no separation clears the bounds), or "-" (text) /
// "" (CSV) where the row has none.
std::string bound_cell(const MtsRow& r, bool full);

// The resolved rows without a finite bound, by why: "no finite bound (WHY): N rows, PAIR at Z to
// PAIR at Z", one line per reason.
std::vector<std::string> rows_without_bound(const Scene& scene, const std::vector<MtsRow>& rows);

// The wide table's second grid: mts_bound per pair by distance, with the model's name and, under
// it, the rows without a bound and why.
std::string bound_grid(const Scene& scene, const std::vector<MtsRow>& rows, bool markdown);

}  // namespace depthprec
