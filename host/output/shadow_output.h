// `depthprec shadow`'s output from its header and cascade records (host/shadow/shadow_run.h):
// text and Markdown as two captioned tables (the biases per cascade, the engines' settings), CSV
// as one row per cascade and engine, JSON as the records themselves.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/output/text_table.h"

namespace depthprec {

// The two tables as columns and text cells, with what each says above it: the text and Markdown
// output and the report page's shadow section render the same.
struct ShadowTables {
  std::string caption, engine_caption, rendered_caption;
  std::vector<Column> cascade_cols, engine_cols, rendered_cols;
  Cells cascades, engines, rendered;  // rendered: cascades checked on OpenGL (--source rendered)
};
ShadowTables shadow_tables(const nlohmann::json& header, const std::vector<nlohmann::json>& records,
                           const std::string& format);

std::string render_shadow_output(const nlohmann::json& header,
                                 const std::vector<nlohmann::json>& records,
                                 const std::string& format);

}  // namespace depthprec
