#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "host/output/text_table.h"
#include "tests/support/run_cli.h"

using Catch::Matchers::Contains;
using depthprec::test::fresh;
using depthprec::test::run_cli;
using depthprec::test::slurp;

namespace {
const std::string kSmallOptions = "--kernel 24x24 --frames 6 --distances 2,1024 ";
}  // namespace

TEST_CASE("mts prints one row per pair and distance with the fields of docs/spec.md 5.4",
          "[cli][mts]") {
  const auto r = run_cli("mts -t standard,reversed -f unorm24 --format-out csv " + kSmallOptions);
  REQUIRE(r.exit_code == 0);
  std::istringstream lines(r.output);
  std::string header, line;
  std::getline(lines, header);
  CHECK(header ==
        "technique,format,depth_range,z,mts,mts_bound,mts_paper,orientations,convergence,lo,hi,"
        "mts_seen,vertex_bound,mts/vb,mts_upper,verdict,probes,frames,"
        "fragment_pairs,launches,seconds,kernel_s,bound_model,bound_by,flags");
  // Under the paper's sampling the worst-case columns are left out, as before it existed.
  const auto paper =
      run_cli("mts -t standard -f unorm24 --format-out csv --set sampling=paper " + kSmallOptions);
  REQUIRE(paper.exit_code == 0);
  CHECK(paper.output.rfind("technique,format,depth_range,z,mts,mts_bound,lo,hi,", 0) == 0);
  std::vector<std::string> rows;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    size_t end = 0;
    for (int field = 0; field < 4; ++field) end = line.find(',', end + (field ? 1 : 0));
    rows.push_back(line.substr(0, end));  // technique, format, depth range, z
  }
  // one row per pair and distance, pairs in order, each in its technique's own depth range
  CHECK(rows == std::vector<std::string>{"standard,unorm24,gl,2", "standard,unorm24,gl,1024",
                                         "reversed,unorm24,zero_to_one,2",
                                         "reversed,unorm24,zero_to_one,1024"});
}

TEST_CASE("no-timing output is byte-identical across runs", "[cli][mts]") {
  const auto a = run_cli("mts -t log_vertex -f e4m12 --no-timing " + kSmallOptions);
  const auto b = run_cli("mts -t log_vertex -f e4m12 --no-timing " + kSmallOptions);
  REQUIRE(a.exit_code == 0);
  CHECK(a.output == b.output);
  CHECK_THAT(a.output, !Contains("seconds"));
}

TEST_CASE("table in every output format", "[cli][table]") {
  const std::string args = "table -t linear,w_buffer -f unorm16 --no-timing " + kSmallOptions;
  const auto md = run_cli(args + "--format-out markdown");
  REQUIRE(md.exit_code == 0);
  CHECK_THAT(md.output, Contains("| z |") || Contains("|    z |") || Contains("| z"));
  CHECK_THAT(md.output, Contains("linear/unorm16/gl"));
  const auto csv = run_cli(args + "--format-out csv");
  REQUIRE(csv.exit_code == 0);
  // The header is the first line; each pair's flags are a column beside its MTS.
  CHECK(csv.output.rfind("z,vertex_bound,linear/unorm16/gl,linear/unorm16/gl mts_bound,"
                         "linear/unorm16/gl flags,"
                         "linear/unorm16/gl mts_paper,linear/unorm16/gl convergence,"
                         "w_buffer/unorm16/gl,w_buffer/unorm16/gl mts_bound,"
                         "w_buffer/unorm16/gl flags,"
                         "w_buffer/unorm16/gl mts_paper,w_buffer/unorm16/gl convergence\n",
                         0) == 0);
  CHECK_THAT(csv.output, Contains(",below_one_code,"));
  const auto js = run_cli(args + "--format-out json");
  REQUIRE(js.exit_code == 0);
  const auto j = nlohmann::json::parse(js.output);
  CHECK(j["program"] == "depthprec");
  CHECK(j["rows"].size() == 4);
  CHECK(j["kernel_variants"].size() == 2);
  CHECK(j["fragment_pairs"].get<long long>() > 0);
  CHECK(j["scene"]["kernel"][0] == 24);
  CHECK_FALSE(j.contains("wall_seconds"));
  // Distances given in any order: the table's rows (and the bound's grid) run nearest first.
  const auto unsorted = run_cli(
      "table -t linear -f unorm16 --no-timing --distances 64,2 --kernel 24x24 --frames 6 "
      "--format-out csv");
  REQUIRE(unsorted.exit_code == 0);
  const size_t row2 = unsorted.output.find("\n2,"), row64 = unsorted.output.find("\n64,");
  REQUIRE(row2 != std::string::npos);
  REQUIRE(row64 != std::string::npos);
  CHECK(row2 < row64);
}

// The worst case searches the paper's first frame at every distance of a pair at once, in an
// evaluator of one frame whose plane-A cache holds many more distances than the paper's frames':
// the run primes PoCL's launches for it too (a launch wider than primed is an internal error).
TEST_CASE("a worst case over many distances launches no wider than it primed", "[cli][mts]") {
  std::string distances;
  for (int i = 0; i < 60; ++i)
    distances += fmt::format("{}{:.4f}", i ? "," : "", 1.005 * std::pow(2.0, i / 2.0));
  const auto r = run_cli("mts -t standard,reversed -f float32 --distances " + distances +
                         " --jobs 2 --no-timing --format-out csv -q");
  INFO(r.output.substr(0, 400));
  REQUIRE(r.exit_code == 0);
  CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 121);  // header and 120 rows
}

TEST_CASE("output option writes the file and an unwritable path fails before the run",
          "[cli][table]") {
  const std::string path = fresh("/tmp/depthprec_test_table.csv");
  std::remove(path.c_str());
  const auto r =
      run_cli("table -t linear -f unorm24 --format-out csv -o " + path + " " + kSmallOptions);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(slurp(path), Contains("linear/unorm24/gl"));
  const auto bad = run_cli("table -o /nonexistent-dir/x.csv " + kSmallOptions);
  CHECK(bad.exit_code == 5);
  CHECK_THAT(bad.output, Contains("cannot write output '/nonexistent-dir/x.csv'"));
}

TEST_CASE("verbose mode names the kernel variants built and only the ones needed", "[cli][mts]") {
  const auto r = run_cli("-v mts -t standard,infinite -f unorm24 " + kSmallOptions);
  REQUIRE(r.exit_code == 0);
  // standard and infinite share one variant (same depth path and format): built once
  size_t n = 0, at = 0;
  while ((at = r.output.find("kernel variant ", at)) != std::string::npos) ++n, ++at;
  CHECK(n == 1);
  CHECK_THAT(r.output, Contains("-DDF_BITS=24u"));
}

TEST_CASE("tradeoff reports every ladder level against the reference with a Pareto front",
          "[cli][tradeoff]") {
  const auto r =
      run_cli("tradeoff -t linear -f unorm24 --distances 4096 --no-timing --format-out json");
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.output);
  REQUIRE(j["levels"].size() == 19);
  CHECK(j["levels"][0]["level"] == "reference");
  CHECK(j["levels"][0]["max_rel_err"] == 0.0);
  // The guaranteed MTS costs something against every level's sampled answer, never less than it.
  for (const auto& l : j["levels"])
    if (!l["median_bound_over_mts"].is_null()) CHECK(l["median_bound_over_mts"].get<double>() >= 1);
  int pareto = 0;
  for (const auto& l : j["levels"]) pareto += l["pareto"].get<bool>() ? 1 : 0;
  CHECK(pareto >= 1);
  // the cheapest level is on the front by construction: nothing does less work
  CHECK(j["levels"][13]["pareto"] == true);
  // the sampling levels: the paper's frames alone, then each round doubling the orientations
  CHECK(j["levels"][14]["sampling"] == "paper");
  CHECK(j["levels"][14]["mean_orientations"] == 100.0);
  for (int k = 15; k < 19; ++k) {
    CHECK(j["levels"][k]["sampling"] == fmt::format("{} round{}", k - 14, k == 15 ? "" : "s"));
    CHECK(j["levels"][k]["mean_orientations"] == 100.0 * (1 << (k - 14)));
    // each round's orientations add work (the first round's searches take the paper's frames
    // one at a time, not with the paper's bisection: they can cost less than it)
    if (k > 15) CHECK(j["levels"][k]["fragment_pairs"] > j["levels"][k - 1]["fragment_pairs"]);
  }
  // coarser bisection can only widen the answer: 2^-4 is further off than 2^-10
  CHECK(j["levels"][10]["max_rel_err"].get<double>() >=
        j["levels"][7]["max_rel_err"].get<double>());
}

TEST_CASE("cost lists depth-path cost, precision, LJ error and structural costs", "[cli][cost]") {
  const auto r = run_cli(
      "cost -t standard,linear,layered -f unorm24 --distances 64,4096 --kernel 40x40 --frames 10");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Contains("ns/pair"));
  CHECK_THAT(r.output, Contains("no early depth test"));     // linear writes fragment depth
  CHECK_THAT(r.output, Contains("3 passes"));                // layered, 3 layers
  CHECK_THAT(r.output, Contains("projection matrix only"));  // standard
}

TEST_CASE("plot renders an MTS JSON output through gnuplot", "[cli][plot]") {
  const std::string json = fresh("/tmp/depthprec_test_plot.json"),
                    png = fresh("/tmp/depthprec_test_plot.png");
  std::remove(png.c_str());
  REQUIRE(run_cli("mts -t standard,linear -f unorm24 --format-out json -o " + json + " " +
                  kSmallOptions)
              .exit_code == 0);
  const auto r = run_cli("plot " + json + " -o " + png);
  REQUIRE(r.exit_code == 0);
  const std::string bytes = slurp(png);
  REQUIRE(bytes.size() > 1000);
  CHECK(bytes.substr(1, 3) == "PNG");
  const auto bad = run_cli("plot " + json + " -o /tmp/x.gif");
  CHECK(bad.exit_code == 3);
  CHECK_THAT(bad.output, Contains(".png or .svg"));
  const auto notjson = run_cli("plot /etc/hostname");
  CHECK(notjson.exit_code == 3);
  // The plots that dash their own lines: a --profiles output's and compare's.
  const std::string profiles = fresh("/tmp/depthprec_test_plot_profiles.json"),
                    profiles_png = fresh("/tmp/depthprec_test_plot_profiles.png"),
                    compare_png = fresh("/tmp/depthprec_test_plot_compare.png");
  REQUIRE(run_cli("mts --profiles ideal,llvmpipe -t standard -f unorm24 --format-out json -o " +
                  profiles + " " + kSmallOptions)
              .exit_code == 0);
  const auto by_profile = run_cli("plot " + profiles + " -o " + profiles_png);
  INFO(by_profile.output);
  CHECK(by_profile.exit_code == 0);
  CHECK(slurp(profiles_png).substr(1, 3) == "PNG");
  const auto compared = run_cli("compare -q -t standard -f unorm24 " + kSmallOptions +
                                "--no-timing --plot " + compare_png);
  INFO(compared.output);
  CHECK(compared.exit_code == 0);
  CHECK(slurp(compare_png).substr(1, 3) == "PNG");
}

TEST_CASE("the MTS plot names the user's scene and marks distances without an MTS", "[cli][plot]") {
  const std::string scene = fresh("/tmp/depthprec_test_harbour.json"),
                    json = fresh("/tmp/depthprec_test_harbour_rows.json"),
                    svg = fresh("/tmp/depthprec_test_harbour.svg");
  std::ofstream(scene) << R"({"far": 1000, "distances": [2, 64, 4096]})";
  REQUIRE(run_cli("mts " + scene + " -t standard -f unorm24 --kernel 16x16 --frames 4 " +
                  "--no-timing --format-out json -o " + json)
              .exit_code == 0);
  REQUIRE(run_cli("plot " + json + " -o " + svg).exit_code == 0);
  const std::string text = slurp(svg);
  // the scene is named after its file (with +set: the command line changed it), not gilg2021
  CHECK_THAT(text, Contains("scene depthprec_test_harbour+set"));
  CHECK_THAT(text, !Contains("gilg2021"));
  // z = 4096 is beyond the far plane: marked, in the key and as a point
  CHECK_THAT(text, Contains("no MTS at this z"));
}

// Before, a scene file without a description carried the default scene's ("the paper's MTS
// configuration. The embedded default scene; ..."), and a report printed it as the user's.
TEST_CASE("a scene file does not inherit the default scene's description", "[cli][scene]") {
  const std::string scene = fresh("/tmp/depthprec_test_bare_scene.json"),
                    json = fresh("/tmp/depthprec_test_bare_rows.json"),
                    html = fresh("/tmp/depthprec_test_bare.html");
  const std::string run =
      " -t standard -f unorm24 --distances 2 --kernel 16x16 --frames 4 -q "
      "--no-timing --format-out json -o " +
      json;
  std::ofstream(scene) << R"({"far": 1000})";
  REQUIRE(run_cli("mts " + scene + run).exit_code == 0);
  CHECK(nlohmann::json::parse(slurp(json))["scene"]["description"] == "");
  REQUIRE(run_cli("report --from " + json + " -q -o " + html).exit_code == 0);
  CHECK_THAT(slurp(html),
             Contains("depthprec_test_bare_scene") && !Contains("The embedded default scene"));
  std::ofstream(scene) << R"({"far": 1000, "description": "a harbour at dusk"})";
  REQUIRE(run_cli("mts " + scene + run).exit_code == 0);
  CHECK(nlohmann::json::parse(slurp(json))["scene"]["description"] == "a harbour at dusk");
  // the default scene keeps its own
  REQUIRE(run_cli("mts" + run).exit_code == 0);
  CHECK_THAT(nlohmann::json::parse(slurp(json))["scene"]["description"].get<std::string>(),
             Contains("The embedded default scene"));
}

TEST_CASE("tradeoff, cost and lj-table plot through gnuplot with --plot", "[cli][plot]") {
  const std::string a = fresh("/tmp/depthprec_test_tradeoff.svg"),
                    b = fresh("/tmp/depthprec_test_lj.png");
  std::remove(a.c_str());
  std::remove(b.c_str());
  REQUIRE(run_cli("tradeoff -t linear -f unorm16 --distances 4096 --plot " + a).exit_code == 0);
  // the front is drawn on the axis it is computed on
  CHECK_THAT(slurp(a),
             Contains("<svg") && Contains("Pareto front") && Contains("fragment pairs evaluated"));
  REQUIRE(run_cli("lj-table --samples 2000 --plot " + b).exit_code == 0);
  CHECK(slurp(b).substr(1, 3) == "PNG");
  const std::string c = fresh("/tmp/depthprec_test_lj.svg");
  REQUIRE(run_cli("lj-table --samples 2000 --plot " + c).exit_code == 0);
  CHECK_THAT(slurp(c), !Contains("0.0000"));  // powers of ten, not 0.000010
  const auto no_time = run_cli(
      "cost -t standard -f unorm24 --distances 64 --kernel 16x16 --frames 4 --no-timing --plot "
      "/tmp/x.png");
  CHECK(no_time.exit_code == 2);
  CHECK_THAT(no_time.output, Contains("--plot needs the timing pass"));
}

TEST_CASE("pipelines compares matrix precision and composition per pair", "[cli][pipelines]") {
  const auto r =
      run_cli("pipelines -t reversed_infinite,standard -f float32 --depth-range zero_to_one " +
              kSmallOptions + "--no-timing --format-out csv --set sampling=paper");
  REQUIRE(r.exit_code == 0);
  std::istringstream lines(r.output);
  std::string line, header;
  std::vector<std::string> rows;
  while (std::getline(lines, line))
    if (line.rfind("pair,", 0) == 0)
      header = line;
    else if (line.find("/float32/") != std::string::npos)
      rows.push_back(line);
  CHECK(r.output.rfind("pair,", 0) == 0);  // CSV starts with its header, no caption
  CHECK_THAT(header, Contains("double/premultiplied farthest"));
  REQUIRE(rows.size() == 2);
  // reversed_infinite's third row of P is (0, 0, 0, n): the same in binary32 and binary64, and
  // its premultiplied product rounds the same way at n = 1, so on the paper's frames every ratio
  // is 1 (over the worst case's orientations the binary64 model matrices meet other roundings,
  // and ratios within the bisection's precision of 1)
  CHECK(rows[0] == "reversed_infinite/float32/zero_to_one,1,1,0,1,1,0,1,1,0");
}

TEST_CASE("table --attribute marks each cell with its dominant factor", "[cli][table]") {
  const auto r = run_cli("table -t reversed -f unorm24,float32 --depth-range zero_to_one " +
                         kSmallOptions + "--no-timing --attribute");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Contains("S / A / V: the dominant factor"));
  CHECK_THAT(r.output, Contains("storage"));  // reversed/unorm24 at 1024 is storage-limited
  const auto j = run_cli("mts -t reversed -f unorm24 --depth-range zero_to_one " + kSmallOptions +
                         "--no-timing --attribute --format-out json");
  REQUIRE(j.exit_code == 0);
  const auto out = nlohmann::json::parse(j.output);
  for (const auto& row : out["rows"]) {
    CHECK(row.contains("storage_mts"));
    CHECK(row.contains("arithmetic_mts"));
    CHECK(row.contains("dominant"));
  }
}

// A terminal is 80-120 columns: text wider than 120 wraps every line. Wide tables split into
// blocks that repeat the columns naming a row; prose folds.
TEST_CASE("text output fits 120 columns and keeps every column", "[cli][text]") {
  const auto widest = [](const std::string& text) {
    size_t w = 0, start = 0;
    while (start < text.size()) {
      size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      w = std::max(w, end - start);
      start = end + 1;
    }
    return w;
  };
  const std::string small = "--distances 2,1024 --frames 2 --kernel 40x40";
  const auto table = run_cli("table -q " + small);
  REQUIRE(table.exit_code == 0);
  CHECK(widest(table.output) <= 120);
  for (const char* label :
       {"standard/float32/gl", "reversed_infinite/unorm24/zero_to_one", "layered/unorm24/gl"})
    CHECK_THAT(table.output, Contains(label));
  const auto mts = run_cli("mts -q -t standard,linear -f unorm24 --attribute " + small);
  REQUIRE(mts.exit_code == 0);
  CHECK(widest(mts.output) <= 120);
  for (const char* column : {"mts_seen", "verdict", "storage_mts", "dominant", "flags"})
    CHECK_THAT(mts.output, Contains(column));
  for (const std::string& args : {"cost -q -t standard,log_fragment -f unorm24 " + small,
                                  "pipelines -q -t standard -f unorm24 " + small,
                                  "compare -q -t standard -f unorm24 " + small}) {
    INFO(args);
    const auto r = run_cli(args);
    REQUIRE(r.exit_code == 0);
    CHECK(widest(r.output) <= 120);
  }
  // The full width stays in Markdown, for pasting into a page that scrolls.
  const auto md = run_cli("table -q --format-out markdown " + small);
  CHECK(widest(md.output) > 120);
}

// Found by the shard fuzzer: a word longer than a line (here a 130-character format name in a
// merged shard) made the folding loop forever, growing its output until memory ran out.
TEST_CASE("folding text leaves a word longer than a line whole and terminates", "[text][fuzz]") {
  const std::string word(130, 'x');
  CHECK(depthprec::wrap_text(word) == word);
  CHECK(depthprec::wrap_text("a " + word) == "a\n  " + word);
  const std::string indented = "   " + word + " tail";
  CHECK(depthprec::wrap_text(indented) ==
        indented);  // only the indent and one space before the tail fit
  const std::string prose = std::string(100, 'a') + " " + std::string(30, 'b');
  CHECK(depthprec::wrap_text(prose) == std::string(100, 'a') + "\n  " + std::string(30, 'b'));
  const auto r =
      run_cli("merge '" + std::string(DEPTHPREC_SOURCE_DIR) +
              "/tests/fuzz/regressions/shard-with-a-format-name-longer-than-a-line.json'");
  CHECK(r.exit_code == 3);  // the format does not exist; no endless folding on the way
}

TEST_CASE("text measures UTF-8 in characters: a cut name's '…' is one column", "[text]") {
  CHECK(depthprec::display_width("caf\u00e9 \u2026") == 6);
  CHECK(depthprec::shortened("short", 24) == "short");
  const std::string cut = depthprec::shortened(std::string(20, 'a') + std::string(20, 'b'), 10);
  CHECK(cut == "aaaaa\u2026bbbb");
  CHECK(depthprec::display_width(cut) == 10);
  // characters, not bytes, are kept whole
  CHECK(depthprec::shortened(std::string(12, 'a') + "\u00e9\u00e9\u00e9", 10) ==
        "aaaaa\u2026a\u00e9\u00e9\u00e9");
  // 119 characters fit a line of 120, though "…" takes three bytes
  const std::string line = std::string(60, 'a') + " \u2026" + std::string(57, 'b');
  CHECK(depthprec::wrap_text(line) == line);
  // a table's columns align by characters
  const std::string t =
      depthprec::grid({{"name", true}, {"n"}}, {{"a\u2026b", "1"}, {"abcd", "22"}}, false);
  CHECK(t == "name   n\na\u2026b    1\nabcd  22\n");
}

TEST_CASE("a non_monotone row says why, and the witness survives the worst case", "[cli][mts]") {
  // standard/unorm24 at 4096 in gl: a search over one set of frames met a clean separation below
  // a fighting one, and the worst case then raised the MTS above both.
  const auto r = run_cli("mts -t standard -f unorm24 --distances 4096 --no-timing -q");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Contains("non_monotone (clean at "));
  const auto j = run_cli(
      "mts -t standard -f unorm24 --distances 4096 --no-timing -q "
      "--format-out json");
  REQUIRE(j.exit_code == 0);
  const auto row = nlohmann::json::parse(j.output)["rows"][0];
  REQUIRE(row["flags"] == "non_monotone");
  const double clean = row["monotone_clean"].get<double>(),
               fight = row["monotone_fight"].get<double>();
  CHECK(clean < fight);
  CHECK(fight <= row["mts"].get<double>());  // the row's MTS lies above every fight it saw
}

TEST_CASE("rows that left kernel pixels uncovered say what covers them", "[cli][mts]") {
  // At 40 degrees the default planes (1.1 times the view's height) leave the kernel's corners
  // bare at some orientations; 3 times cover them.
  const std::string base =
      "mts -t standard -f unorm24 --distances 100 --frames 8 --kernel 32x32 --set sampling=paper "
      "--set rotation_range_deg=40 --no-timing -q";
  const auto bare = run_cli(base);
  REQUIRE(bare.exit_code == 0);
  CHECK_THAT(bare.output, Contains("1 of 1 rows left kernel pixels uncovered"));
  CHECK_THAT(bare.output, Contains("--set plane_margin="));
  const auto covered = run_cli(base + " --set plane_margin=3");
  REQUIRE(covered.exit_code == 0);
  CHECK_THAT(covered.output, !Contains("uncovered"));
}

TEST_CASE("the table's note of rows without a bound counts one row as one", "[cli][bound]") {
  // reversed/unorm24 at 2e7: no separation up to max_separation_factor z clears the bounds.
  const auto r =
      run_cli("table -t reversed -f unorm24 --distances 2e7 " + depthprec::test::kSmallScene);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Contains("clears the error bounds): 1 row,"));
  CHECK_THAT(r.output, !Contains("1 rows") && !Contains(" to reversed/unorm24"));
}

TEST_CASE("pairs named on the command line make another scene, named so", "[cli]") {
  // -t/-f/--depth-range replace the scene's pairs, as a --set changes a key: "+set", as docs/cli.md
  // promises, so an output never labels the changed scene with the default's name alone.
  // No other option: a --kernel or --frames adds "+set" by itself.
  const auto r = run_cli(
      "world -t reversed -f float32 --distance 100 --separation 0.01 --transforms absolute -q "
      "--format-out json");
  REQUIRE(r.exit_code == 0);
  CHECK(nlohmann::json::parse(r.output)["scene_name"] == "gilg2021+set");
}
