// Renders MTS results: the long form (one line per pair and distance, every field of
// docs/spec.md 5.4) and the batch precision table (one row per distance, one column per pair), as
// aligned text, CSV, JSON (with a header object) or Markdown.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "host/model/scene.h"
#include "host/mts/mts_row.h"
#include "host/mts/run_info.h"
#include "host/output/text_table.h"  // human, exact, number_cell

namespace depthprec {

// A table cell: the MTS, or the verdict that replaces it (unresolvable stays "inf", Gilg's ∞);
// exact digits when full, else 4 significant ones.
std::string table_cell(const MtsRow& r, bool full);
// " S", " A" or " V" after a table cell: the dominant factor of an attributed row whose cell is
// its MTS or inf ("" otherwise: a verdict such as clipped has no factor to name).
std::string dominant_mark(const MtsRow& r);
// The line under a table: the work done, and the time it took when measured.
std::string footer(const RunInfo& run);

std::string render_rows(const Scene& scene, const std::vector<MtsRow>& rows, const RunInfo& run,
                        const std::string& format);
std::string render_table(const Scene& scene, const std::vector<MtsRow>& rows, const RunInfo& run,
                         const std::string& format);

// Whether path is a device or a pipe (/dev/null, /dev/stdout, a FIFO): written in place, never
// replaced through a temporary file (as root, a rename over /dev/null would put a regular file
// there), and with no journal beside it.
bool is_stream_output(const std::string& path);
// Writes text to path atomically (temporary file, then rename), a stream output in place, or to
// stdout when path is "". Throws OutputError naming the path.
void write_output(const std::string& path, const std::string& text);
// Fails early, before a long run, when path cannot be written.
void check_writable(const std::string& path);

}  // namespace depthprec
