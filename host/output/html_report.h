// The shareable report (`depthprec report`): one self-contained HTML page -- the scene, the MTS
// table, the plot with the vertex bound (inline SVG), the attribution and the Lapidous-Jiao
// figures -- with no script, stylesheet, font or image from anywhere else.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/model/scene.h"
#include "host/mts/mts_row.h"
#include "host/output/report.h"

namespace depthprec {

// The Lapidous-Jiao average error of a pair whose technique is one of LJ99's buffers.
struct LjFigure {
  std::string pair, buffer, format;
  double ae = 0;
};

struct ReportPage {
  const Scene* scene = nullptr;
  std::vector<MtsRow> rows;  // scene order; attributed rows add the factor table
  RunInfo run;
  std::vector<LjFigure> lj;
  std::string plot_svg;  // gnuplot's SVG document, inlined
  std::string command;   // the command line that made the page
  // `shadow`'s header and cascade records, when the scene has a "shadow" block (docs/shadow.md)
  nlohmann::json shadow_header;
  std::vector<nlohmann::json> shadow_records;
};

std::string html_report(const ReportPage& page);

// Text safe inside HTML elements and attribute values.
std::string html_escape(const std::string& s);

}  // namespace depthprec
