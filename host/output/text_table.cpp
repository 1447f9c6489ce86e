#include "host/output/text_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace depthprec {

std::string human(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return "nan";
  if (v == 0) return "0";
  return fmt::format("{:.4g}", v);
}

std::string exact(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.17g}", v);
}

std::string number_cell(double v, const std::string& format, const char* text) {
  return format == "csv" ? exact(v) : fmt::format(fmt::runtime(text), v);
}

// Aligned text or Markdown from a header and string cells.
namespace {

// Aligned text wider than a terminal wraps every line and cannot be read: text (not Markdown,
// whose readers scroll) is split into blocks of columns no wider than this, each block repeating
// the key columns that name a row.
constexpr size_t kTextWidth = 120;

// The columns that name a row: the leading names (left-aligned), and a distance `z` right after
// them; the first column when there are no names.
size_t key_columns(const std::vector<Column>& cols) {
  size_t k = 0;
  while (k < cols.size() && cols[k].left) ++k;
  if (k < cols.size() && cols[k].name == "z") ++k;
  return std::max<size_t>(k, 1);
}

std::string one_grid(const std::vector<Column>& cols, const Cells& cells, bool markdown);

// A cell padded with spaces to `width` columns, on the right of a left-aligned cell.
std::string padded(const std::string& cell, size_t width, bool left) {
  const std::string pad(width - std::min(width, display_width(cell)), ' ');
  return left ? cell + pad : pad + cell;
}

std::string text_blocks(const std::vector<Column>& cols, const Cells& cells) {
  std::vector<size_t> w(cols.size());
  for (size_t c = 0; c < cols.size(); ++c) {
    w[c] = display_width(cols[c].name);
    for (const auto& row : cells) w[c] = std::max(w[c], display_width(row[c]));
  }
  size_t total = 0;
  for (size_t c = 0; c < cols.size(); ++c) total += w[c] + (c ? 2 : 0);
  const size_t key = key_columns(cols);
  if (total <= kTextWidth || key >= cols.size()) return one_grid(cols, cells, false);
  size_t key_width = 0;
  for (size_t c = 0; c < key; ++c) key_width += w[c] + (c ? 2 : 0);
  std::string out;
  for (size_t first = key; first < cols.size();) {
    size_t last = first, width = key_width + 2 + w[first];
    while (last + 1 < cols.size() && width + 2 + w[last + 1] <= kTextWidth) width += 2 + w[++last];
    std::vector<Column> bc(cols.begin(), cols.begin() + key);
    bc.insert(bc.end(), cols.begin() + first, cols.begin() + last + 1);
    Cells bcells;
    for (const auto& row : cells) {
      std::vector<std::string> r(row.begin(), row.begin() + key);
      r.insert(r.end(), row.begin() + first, row.begin() + last + 1);
      bcells.push_back(r);
    }
    out += (out.empty() ? "" : "\n") + one_grid(bc, bcells, false);
    first = last + 1;
  }
  return out;
}

}  // namespace

size_t display_width(const std::string& s) {
  // UTF-8: every byte but the continuation bytes (10xxxxxx) starts a character
  return static_cast<size_t>(std::count_if(
      s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

std::string shortened(const std::string& s, size_t width) {
  if (width < 3 || display_width(s) <= width) return s;
  // byte offsets of the characters' starts
  std::vector<size_t> starts;
  for (size_t i = 0; i < s.size(); ++i)
    if ((static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) starts.push_back(i);
  const size_t head = (width - 1) * 3 / 5, tail = width - 1 - head;
  return s.substr(0, starts[head]) + "\u2026" + s.substr(starts[starts.size() - tail]);
}

namespace {

// The byte offset of character `column` (0-based) of s, or s.size() past its end.
size_t byte_of_column(const std::string& s, size_t column) {
  for (size_t i = 0; i < s.size(); ++i)
    if ((static_cast<unsigned char>(s[i]) & 0xC0) != 0x80 && column-- == 0) return i;
  return s.size();
}

}  // namespace

std::string wrap_text(const std::string& text) {
  std::string out;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    while (display_width(line) > kTextWidth) {
      // Fold at the last space that follows text; a line whose only spaces are its indent (a
      // word longer than the width) stays as it is. Each fold leaves less text after the indent.
      const size_t lead = line.find_first_not_of(' ');
      const size_t cut = line.rfind(' ', byte_of_column(line, kTextWidth));
      if (cut == std::string::npos || lead == std::string::npos || cut <= lead) break;
      out += line.substr(0, cut) + "\n";
      line = "  " + line.substr(line.find_first_not_of(' ', cut));
    }
    out += line;
    if (end < text.size()) out += "\n";
    start = end + 1;
  }
  return out;
}

std::string grid(const std::vector<Column>& cols, const Cells& cells, bool markdown) {
  return markdown ? one_grid(cols, cells, true) : text_blocks(cols, cells);
}

namespace {

std::string one_grid(const std::vector<Column>& cols, const Cells& cells, bool markdown) {
  std::vector<size_t> w(cols.size());
  for (size_t c = 0; c < cols.size(); ++c) {
    w[c] = display_width(cols[c].name);
    for (const auto& row : cells) w[c] = std::max(w[c], display_width(row[c]));
  }
  auto line = [&](const std::vector<std::string>& v) {
    std::string s = markdown ? "|" : "";
    for (size_t c = 0; c < cols.size(); ++c) {
      const std::string cell = padded(v[c], w[c], cols[c].left);
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

// RFC 4180: a field holding a comma, a quote or a line break is quoted, its quotes doubled.
std::string csv_field(const std::string& f) {
  if (f.find_first_of(",\"\n\r") == std::string::npos) return f;
  std::string q = "\"";
  for (char c : f) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string out;
  for (size_t c = 0; c < fields.size(); ++c) out += (c ? "," : "") + csv_field(fields[c]);
  return out + "\n";
}

}  // namespace

std::string csv(const std::vector<Column>& cols, const Cells& cells) {
  std::vector<std::string> names;
  for (const auto& c : cols) names.push_back(c.name);
  std::string out = csv_line(names);
  for (const auto& row : cells) out += csv_line(row);
  return out;
}

std::string render_cells(const std::vector<Column>& cols, const Cells& cells,
                         const std::string& format) {
  if (format == "csv") return csv(cols, cells);
  return grid(cols, cells, format == "markdown");
}

std::string captioned(const std::string& caption, const std::vector<Column>& cols,
                      const Cells& cells, const std::string& format) {
  return (format == "csv" ? "" : caption + "\n\n") + render_cells(cols, cells, format);
}

}  // namespace depthprec
