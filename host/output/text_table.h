// Renders a table of string cells as aligned text, Markdown or CSV: the one formatter every
// command's tabular output goes through.
#pragma once

#include <string>
#include <vector>

namespace depthprec {

std::string human(double v);  // 4 significant digits, "inf", "0"
std::string exact(double v);  // round-trippable binary64
// A number as `format` prints it: exact in CSV (a data format), in text and Markdown as human()
// does or as the fmt spec `text` says ("{:.3f}").
inline std::string number_cell(double v, const std::string& format) {
  return format == "csv" ? exact(v) : human(v);
}
std::string number_cell(double v, const std::string& format, const char* text);

struct Column {
  std::string name;
  bool left = false;  // left-aligned (names), else right-aligned (numbers)
};

using Cells = std::vector<std::vector<std::string>>;

// Columns a cell takes on a terminal: its UTF-8 characters (a name's "é" or "…" is one).
size_t display_width(const std::string& s);
// s cut to `width` characters, its middle replaced by "…": the start and the end stay, where
// names usually differ (a path, a level of detail, an index).
std::string shortened(const std::string& s, size_t width);

// Aligned text or Markdown. Text wider than 120 columns is split into blocks of columns, each
// repeating the columns that name a row (the leading names and a following `z`).
std::string grid(const std::vector<Column>& cols, const Cells& cells, bool markdown);
std::string csv(const std::vector<Column>& cols, const Cells& cells);
// Prose lines of text output folded at spaces to the same 120 columns (lines that fit, and
// words longer than the width, are left as they are).
std::string wrap_text(const std::string& text);
// wrap_text for the text format, other formats unchanged.
inline std::string for_terminal(const std::string& out, const std::string& format) {
  return format == "text" ? wrap_text(out) : out;
}
// A table under a caption in text and Markdown. CSV is the header line and the rows alone, so
// a CSV reader gets the table as it is; what the caption says is in the columns or in the JSON.
std::string captioned(const std::string& caption, const std::vector<Column>& cols,
                      const Cells& cells, const std::string& format);
// "text", "markdown" or "csv".
std::string render_cells(const std::vector<Column>& cols, const Cells& cells,
                         const std::string& format);

}  // namespace depthprec
