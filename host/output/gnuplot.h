// Runs a gnuplot script to write an image: the one place depthprec calls gnuplot.
#pragma once

#include <string>

namespace depthprec {

// "pngcairo ..." or "svg ..." for a path ending in .png / .svg; throws InputError otherwise.
std::string gnuplot_terminal(const std::string& output);
// A gnuplot string literal.
std::string gnuplot_quote(const std::string& s);
// The file a plot's script sets as gnuplot's output: output.tmp, renamed to output once gnuplot
// has finished, so a failed plot leaves neither a half-drawn image nor the temporary file; a
// device or pipe (/dev/stdout) is written in place.
std::string gnuplot_writes(const std::string& output);
// Writes the script to a temporary file and runs gnuplot on it, then puts what it wrote
// (gnuplot_writes) in place. Throws RuntimeError when gnuplot is missing (naming the package),
// OutputError when it fails.
void run_gnuplot(const std::string& script, const std::string& output);

// Checks up front, before a batch runs, that a plot can be written there: a .png or .svg name in
// a writable place ("" is no plot). Throws InputError / OutputError.
void check_plot_output(const std::string& path);

}  // namespace depthprec
