// Renders a table of string cells as aligned text, Markdown or CSV: the one formatter every
// command's tabular output goes through.
#pragma once

#include <string>
#include <vector>

namespace depthprec {

struct Column {
  std::string name;
  bool left = false;  // left-aligned (names), else right-aligned (numbers)
};

using Cells = std::vector<std::vector<std::string>>;

std::string grid(const std::vector<Column>& cols, const Cells& cells, bool markdown);
std::string csv(const std::vector<Column>& cols, const Cells& cells);
// "text", "markdown" or "csv".
std::string render_cells(const std::vector<Column>& cols, const Cells& cells,
                         const std::string& format);

}  // namespace depthprec
