// The plots the batch commands draw with --plot, through gnuplot (host/output/gnuplot.h).
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/analysis/tradeoff.h"
#include "host/mts/mts_row.h"

namespace depthprec {

struct CostPoint {
  std::string label;
  double ns = 0, median = 0;
};

// Precision against cost: one labelled point per technique x format.
void plot_cost(const std::vector<CostPoint>& points, const std::string& output);

// Error against work (fragment pairs): one point per level, the Pareto front joined. Errors of 0
// sit on a floor.
void plot_tradeoff(const std::vector<LevelResult>& results, const std::string& output);

// MTS against distance, log-log, one line per pair, the binary32 vertex bound shaded beneath (as
// Gilg et al.'s fig. 6); distances without an MTS marked x on a line above the numbers.
void plot_mts(const std::vector<MtsRow>& rows, const std::string& title, const std::string& output);

// LJ error against f/d per format: one panel per buffer type, 16 bits, uniform sampling (the
// records of lj-table by key).
void plot_lj_table(const std::map<std::string, nlohmann::json>& records, const std::string& output);

// Emulated and rendered MTS against distance (log-log, a solid and a dashed line per pair in
// one colour) above their ratio emulated/rendered: the records of `compare`.
void plot_compare(const std::vector<nlohmann::json>& records, const std::string& output);

// MTS against distance under each implementation profile (the records of `--profiles`): per pair
// one colour, a line per profile (solid, dashed, dotted, ...) and the band between the smallest
// and the largest shaded, so where the answer depends on the rasterizer shows as width.
void plot_profiles(const std::vector<nlohmann::json>& records,
                   const std::vector<std::string>& profiles, const std::string& title,
                   const std::string& output);

}  // namespace depthprec
