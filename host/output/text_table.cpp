#include "host/output/text_table.h"

#include <fmt/format.h>

#include <algorithm>

namespace depthprec {

// Aligned text or Markdown from a header and string cells.
std::string grid(const std::vector<Column>& cols, const Cells& cells, bool markdown) {
  std::vector<size_t> w(cols.size());
  for (size_t c = 0; c < cols.size(); ++c) {
    w[c] = cols[c].name.size();
    for (const auto& row : cells) w[c] = std::max(w[c], row[c].size());
  }
  auto line = [&](const std::vector<std::string>& v) {
    std::string s = markdown ? "|" : "";
    for (size_t c = 0; c < cols.size(); ++c) {
      const std::string cell =
          cols[c].left ? fmt::format("{:<{}}", v[c], w[c]) : fmt::format("{:>{}}", v[c], w[c]);
      s += markdown ? " " + cell + " |" : (c ? "  " : "") + cell;
    }
    while (!markdown && !s.empty() && s.back() == ' ') s.pop_back();
    return s + "\n";
  };
  std::vector<std::string> names;
  for (const auto& c : cols) names.push_back(c.name);
  std::string out = line(names);
  if (markdown) {
    std::string sep = "|";
    for (size_t c = 0; c < cols.size(); ++c)
      sep += cols[c].left ? " :" + std::string(w[c] - 1, '-') + " |"
                          : " " + std::string(w[c] - 1, '-') + ": |";
    out += sep + "\n";
  }
  for (const auto& row : cells) out += line(row);
  return out;
}

std::string csv(const std::vector<Column>& cols, const Cells& cells) {
  std::string out;
  for (size_t c = 0; c < cols.size(); ++c) out += (c ? "," : "") + cols[c].name;
  out += "\n";
  for (const auto& row : cells) {
    for (size_t c = 0; c < row.size(); ++c) {
      const bool quote = row[c].find(',') != std::string::npos;
      out += (c ? "," : "") + (quote ? "\"" + row[c] + "\"" : row[c]);
    }
    out += "\n";
  }
  return out;
}

std::string render_cells(const std::vector<Column>& cols, const Cells& cells,
                         const std::string& format) {
  if (format == "csv") return csv(cols, cells);
  return grid(cols, cells, format == "markdown");
}

}  // namespace depthprec
