// `drapelab report` end to end: on a tiny run made here with the CLI, the page is well-formed
// (parsed as XML by libxml2: every element closed, attributes quoted, entities escaped), has one
// SVG per plot with axes, axis titles and a legend naming every solver in one colour per solver,
// and references only files inside the run folder; a sweep folder gets its table and a plot per
// varied key and metric; a folder that is neither exits 2 naming what is missing. Then headless
// Chromium opens the page: the screenshot must not be blank and the console must stay silent. Also
// the report's small parts on their own: CSV reading, tick marks, base64, SVG with missing values.
#include <gtest/gtest.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <png.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "drapelab/report/axis_ticks.hpp"
#include "drapelab/report/html_page.hpp"
#include "drapelab/report/run_completeness.hpp"
#include "drapelab/report/svg_plot.hpp"
#include "drapelab/run_folder/csv.hpp"
#include "fixtures/cli.hpp"

namespace {

namespace fs = std::filesystem;
using drapelab::fixtures::read_text;
using drapelab::fixtures::run_drapelab;
using drapelab::fixtures::write_text;

// A 7 x 7 sheet 0.05 m above a sphere, 0.2 s at 60 frames/s: it lands at about 0.1 s and the
// contact, clearance and distance columns all get values. Two solvers: ours and Bullet's classic.
const std::string kTinyDrape =
    "name: tiny_drape\n"
    "description: a 7 x 7 sheet falls on a sphere\n"
    "duration: 0.2\n"
    "frame_rate: 60\n"
    "cloth:\n"
    "  size: [0.4, 0.4]\n"
    "  resolution: [7, 7]\n"
    "  plane: xz\n"
    "  center: [0, 0.45, 0]\n"
    "  mass: 0.05\n"
    "  thickness: 0.005\n"
    "  springs:\n"
    "    stretch: {ks: 200, kd: 0.01}\n"
    "    shear: {ks: 20, kd: 0.005}\n"
    "    bend: {ks: 2, kd: 0.001}\n"
    "colliders:\n"
    "  - {name: ball, type: sphere, center: [0, 0.2, 0], radius: 0.2}\n"
    "contact: {stiffness: 500, damping: 0.05, friction: 0.3}\n"
    "solvers:\n"
    "  - {name: ours, type: spring_damper}\n"
    "  - {name: bullet_classic, type: bullet_softbody}\n";

const std::vector<std::string> kSolvers{"ours", "bullet_classic"};
// The plots a run with colliders, two solvers and no drape support must have, by title.
const std::vector<std::string> kRunPlots{
    "Kinetic energy",     "Spring energy",   "Max stretch",
    "Min clearance",      "Max penetration", "Triangle penetration",
    "Self-intersections", "Contact force",   "Distance between solvers"};

// ---- a parsed page -------------------------------------------------------------------------

std::string attribute(xmlNode* node, const char* name) {
  xmlChar* value = xmlGetProp(node, reinterpret_cast<const xmlChar*>(name));
  if (!value) return "";
  std::string text(reinterpret_cast<const char*>(value));
  xmlFree(value);
  return text;
}

std::string text_of(xmlNode* node) {
  xmlChar* value = xmlNodeGetContent(node);
  std::string text = value ? reinterpret_cast<const char*>(value) : "";
  xmlFree(value);
  return text;
}

std::string name_of(xmlNode* node) { return reinterpret_cast<const char*>(node->name); }

void collect(xmlNode* node, std::vector<xmlNode*>& out) {
  for (xmlNode* child = node; child; child = child->next) {
    if (child->type != XML_ELEMENT_NODE) continue;
    out.push_back(child);
    collect(child->children, out);
  }
}

// Elements under `root` (itself included) with this tag and, if given, this class.
std::vector<xmlNode*> find(xmlNode* root, const std::string& tag,
                           const std::string& css_class = "") {
  std::vector<xmlNode*> all{root}, found;
  collect(root->children, all);
  for (xmlNode* node : all)
    if (name_of(node) == tag && (css_class.empty() || attribute(node, "class") == css_class))
      found.push_back(node);
  return found;
}

// The page parsed as XML; a parse error fails the test with libxml2's message and line.
class Page {
 public:
  explicit Page(const std::string& html) {
    context_ = xmlNewParserCtxt();
    doc_ = xmlCtxtReadMemory(context_, html.data(), static_cast<int>(html.size()), "report.html",
                             "UTF-8", XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
    well_formed_ = doc_ != nullptr && context_->wellFormed;
    if (!well_formed_) {
      const xmlError* error = xmlCtxtGetLastError(context_);
      error_ = error ? std::string(error->message) + " at line " + std::to_string(error->line)
                     : "no document";
    }
  }
  ~Page() {
    if (doc_) xmlFreeDoc(doc_);
    xmlFreeParserCtxt(context_);
  }
  Page(const Page&) = delete;
  Page& operator=(const Page&) = delete;

  bool well_formed() const { return well_formed_; }
  const std::string& error() const { return error_; }
  xmlNode* root() const { return xmlDocGetRootElement(doc_); }

 private:
  xmlParserCtxtPtr context_ = nullptr;
  xmlDocPtr doc_ = nullptr;
  bool well_formed_ = false;
  std::string error_;
};

// Block elements an HTML parser would move out of a <p> (XML would accept them there).
void expect_no_blocks_in_paragraphs(xmlNode* root) {
  static const std::set<std::string> kBlocks{"div", "p",  "table", "figure", "pre",
                                             "h1",  "h2", "h3",    "ul",     "svg"};
  std::vector<xmlNode*> all{root};
  collect(root->children, all);
  for (xmlNode* node : all) {
    if (name_of(node) != "p") continue;
    std::vector<xmlNode*> inside;
    collect(node->children, inside);
    for (xmlNode* child : inside)
      EXPECT_EQ(kBlocks.count(name_of(child)), 0u) << "<" << name_of(child) << "> inside <p>";
  }
}

// Every src and href: a data: URI, a fragment naming an id on the page, or a relative path to a
// file inside `folder` (resolved from the page's own folder). Returns how many it checks.
int expect_references_inside(xmlNode* root, const fs::path& page, const fs::path& folder) {
  std::set<std::string> ids;
  std::vector<xmlNode*> all{root};
  collect(root->children, all);
  for (xmlNode* node : all)
    if (!attribute(node, "id").empty()) ids.insert(attribute(node, "id"));
  const fs::path inside = fs::weakly_canonical(folder);
  int checked = 0;
  for (xmlNode* node : all) {
    for (const char* name : {"src", "href", "poster", "data"}) {
      const std::string ref = attribute(node, name);
      if (ref.empty()) continue;
      ++checked;
      if (ref.rfind("data:", 0) == 0) continue;
      if (ref[0] == '#') {
        EXPECT_EQ(ids.count(ref.substr(1)), 1u)
            << name << "=\"" << ref << "\" names no id on the page";
        continue;
      }
      EXPECT_EQ(ref.find(':'), std::string::npos) << name << "=\"" << ref << "\" has a scheme";
      EXPECT_FALSE(fs::path(ref).is_absolute()) << name << "=\"" << ref << "\" is absolute";
      const fs::path target = fs::weakly_canonical(page.parent_path() / ref);
      EXPECT_TRUE(fs::is_regular_file(target)) << name << "=\"" << ref << "\": no such file";
      const auto [end, unused] =
          std::mismatch(inside.begin(), inside.end(), target.begin(), target.end());
      EXPECT_TRUE(end == inside.end()) << name << "=\"" << ref << "\" points outside " << folder;
    }
  }
  return checked;
}

// Geometry attributes must be finite numbers (a NaN cell must become a gap, not "nan").
void expect_finite_geometry(xmlNode* svg) {
  std::vector<xmlNode*> all{svg};
  collect(svg->children, all);
  for (xmlNode* node : all) {
    for (const char* name : {"x", "y", "x1", "x2", "y1", "y2", "cx", "cy", "width", "height"}) {
      const std::string value = attribute(node, name);
      if (value.empty()) continue;
      const auto number = drapelab::run_folder::parse_number(value);
      EXPECT_TRUE(number && std::isfinite(*number)) << name << "=\"" << value << "\"";
    }
    const std::string points = attribute(node, "points");
    for (char c : points)
      EXPECT_TRUE(std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == ',' || c == ' ' ||
                  c == '-')
          << points;
  }
}

struct PlotInfo {
  xmlNode* svg = nullptr;
  std::string title;
  std::vector<std::string> legend;            // legend labels
  std::map<std::string, std::string> stroke;  // series label -> colour of its lines
};

// Checks what every plot must have (axes with ticks and labels, titles, a legend) and returns it.
// A y title always gives a unit in parentheses; an x title too when `x_unit` (a sweep's x axis is
// a scene key, in the scene file's units).
PlotInfo inspect_plot(xmlNode* svg, bool x_unit = true) {
  PlotInfo info;
  info.svg = svg;
  const auto titles = find(svg, "text", "plot-title");
  EXPECT_EQ(titles.size(), 1u);
  if (!titles.empty()) info.title = text_of(titles[0]);
  for (const char* axis : {"x-axis", "y-axis"}) {
    const auto groups = find(svg, "g", axis);
    EXPECT_EQ(groups.size(), 1u) << info.title << ": " << axis;
    if (groups.empty()) continue;
    EXPECT_GE(find(groups[0], "line", "tick").size(), 2u) << info.title << ": " << axis << " ticks";
    const auto labels = find(groups[0], "text", "tick-label");
    EXPECT_GE(labels.size(), 2u) << info.title << ": " << axis << " tick labels";
    for (xmlNode* label : labels) EXPECT_FALSE(text_of(label).empty());
    const auto axis_title = find(groups[0], "text", "axis-title");
    EXPECT_EQ(axis_title.size(), 1u) << info.title << ": " << axis << " title";
    if (!axis_title.empty() && (x_unit || std::string(axis) == "y-axis")) {
      EXPECT_NE(text_of(axis_title[0]).find('('), std::string::npos)
          << info.title << ": a unit in parentheses";
    }
  }
  const auto legend = find(svg, "g", "legend");
  EXPECT_EQ(legend.size(), 1u) << info.title;
  if (!legend.empty())
    for (xmlNode* label : find(legend[0], "text", "legend-label"))
      info.legend.push_back(text_of(label));
  for (xmlNode* series : find(svg, "g", "series"))
    for (xmlNode* line : find(series, "polyline"))
      info.stroke[attribute(series, "data-label")] = attribute(line, "stroke");
  expect_finite_geometry(svg);
  return info;
}

std::vector<PlotInfo> plots_of(const Page& page, bool x_unit = true) {
  std::vector<PlotInfo> plots;
  for (xmlNode* svg : find(page.root(), "svg")) {
    EXPECT_EQ(attribute(svg, "class"), "plot");
    plots.push_back(inspect_plot(svg, x_unit));
  }
  return plots;
}

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

// ---- PNG -----------------------------------------------------------------------------------

// Writes a w x h RGB image with a colour gradient (a stand-in for a rendered frame).
void write_gradient_png(const fs::path& path, int w, int h) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(w);
  image.height = static_cast<png_uint_32>(h);
  image.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> pixels(static_cast<std::size_t>(w * h * 3));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      unsigned char* p = &pixels[static_cast<std::size_t>((y * w + x) * 3)];
      p[0] = static_cast<unsigned char>(255 * x / w);
      p[1] = static_cast<unsigned char>(255 * y / h);
      p[2] = 128;
    }
  ASSERT_TRUE(png_image_write_to_file(&image, path.c_str(), 0, pixels.data(), 0, nullptr))
      << image.message;
}

// The number of distinct RGBA colours in a PNG file; -1 when it cannot be decoded.
long distinct_colours(const fs::path& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return -1;
  image.format = PNG_FORMAT_RGBA;
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) return -1;
  std::set<std::uint32_t> colours;
  for (std::size_t k = 0; k + 3 < pixels.size(); k += 4)
    colours.insert(static_cast<std::uint32_t>(pixels[k]) << 24 |
                   static_cast<std::uint32_t>(pixels[k + 1]) << 16 |
                   static_cast<std::uint32_t>(pixels[k + 2]) << 8 | pixels[k + 3]);
  return static_cast<long>(colours.size());
}

// ---- the tests -----------------------------------------------------------------------------

class ReportCli : public drapelab::fixtures::TempDirTest {
 protected:
  // The tiny drape run into dir()/run, made with the CLI.
  fs::path make_run() {
    const fs::path scene = dir() / "tiny_drape.yaml";
    write_text(scene, kTinyDrape);
    const fs::path run = dir() / "run";
    const auto result = run_drapelab({"run", scene.string(), "--out", run.string(), "-q"});
    EXPECT_EQ(result.exit_code, 0) << result.output;
    return run;
  }
};

TEST_F(ReportCli, RunReportIsWellFormedWithOneSvgPerPlotAndLocalReferencesOnly) {
  const fs::path run = make_run();
  const auto result = run_drapelab({"report", run.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const fs::path page_path = run / "report.html";
  EXPECT_NE(result.output.find(page_path.string()), std::string::npos) << "prints the page's path";
  const std::string html = read_text(page_path);
  Page page(html);
  ASSERT_TRUE(page.well_formed()) << page.error();
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(find(page.root(), "script").size(), 0u);
  expect_no_blocks_in_paragraphs(page.root());
  EXPECT_GT(expect_references_inside(page.root(), page_path, run), 0);

  // The scene: name, description, scene.yaml in a <pre>; no render yet, so the page says how.
  EXPECT_NE(html.find("<h1>tiny_drape</h1>"), std::string::npos);
  EXPECT_NE(html.find("a 7 x 7 sheet falls on a sphere"), std::string::npos);
  bool scene_shown = false;
  for (xmlNode* pre : find(page.root(), "pre"))
    scene_shown = scene_shown || text_of(pre) == kTinyDrape;
  EXPECT_TRUE(scene_shown) << "scene.yaml, verbatim, in a <pre>";
  EXPECT_NE(html.find("drapelab render " + run.string()), std::string::npos);
  EXPECT_EQ(find(page.root(), "img").size(), 0u);
  EXPECT_EQ(find(page.root(), "video").size(), 0u);

  // The summary table names both solvers with their status.
  for (const auto& solver : kSolvers) EXPECT_NE(html.find(solver), std::string::npos);

  // One SVG per plot, each with axes and a legend naming each solver, one colour per solver.
  const auto plots = plots_of(page);
  std::vector<std::string> titles;
  for (const auto& plot : plots) titles.push_back(plot.title);
  for (const auto& title : kRunPlots)
    EXPECT_EQ(std::count(titles.begin(), titles.end(), title), 1) << title;
  EXPECT_EQ(plots.size(), kRunPlots.size()) << "no drape plot without a drape support";
  std::map<std::string, std::string> colour;  // solver -> its colour in the first plot
  for (const auto& plot : plots) {
    if (plot.title == "Distance between solvers") {
      EXPECT_TRUE(contains(plot.legend, "ours \u2013 bullet_classic")) << "one line per pair";
      EXPECT_EQ(plot.stroke.size(), 1u);
      continue;
    }
    for (const auto& solver : kSolvers) {
      EXPECT_TRUE(contains(plot.legend, solver)) << plot.title << " legend lacks " << solver;
      ASSERT_EQ(plot.stroke.count(solver), 1u) << plot.title << " draws no line for " << solver;
      const auto [it, first] = colour.try_emplace(solver, plot.stroke.at(solver));
      EXPECT_EQ(it->second, plot.stroke.at(solver))
          << plot.title << ": " << solver << " changes colour";
    }
  }
  EXPECT_NE(colour.at("ours"), colour.at("bullet_classic"));
}

TEST_F(ReportCli, EmbedsTheLastRenderedFrameAndLinksTheVideoRelativeToThePage) {
  const fs::path run = make_run();
  fs::create_directories(run / "render");
  write_gradient_png(run / "render" / "frame_0002.png", 8, 8);
  write_gradient_png(run / "render" / "frame_0010.png", 16, 4);  // the last by number, not by size
  write_gradient_png(run / "render" / "frame_0009.png", 4, 16);
  write_text(run / "render" / "video.mp4", "not really a video");
  fs::create_directories(run / "pages");
  const fs::path page_path = run / "pages" / "tiny.html";
  const auto result = run_drapelab({"report", run.string(), "--out", page_path.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::string html = read_text(page_path);
  Page page(html);
  ASSERT_TRUE(page.well_formed()) << page.error();
  expect_references_inside(page.root(), page_path, run);

  const auto images = find(page.root(), "img");
  ASSERT_EQ(images.size(), 1u);
  EXPECT_EQ(attribute(images[0], "src"),
            "data:image/png;base64," +
                drapelab::report::base64_encode(read_text(run / "render" / "frame_0010.png")));
  const auto videos = find(page.root(), "video");
  ASSERT_EQ(videos.size(), 1u);
  EXPECT_EQ(attribute(videos[0], "src"), "../render/video.mp4");
}

// A sweep folder as drapelab sweep writes it: two varied keys (one numeric over three decades, one
// a list), two solvers, one failed run with no measurements, a message with a comma.
const std::string kSweepCsv =
    "combination,cloth.springs.stretch.ks,cloth.resolution,solver,type,status,exit_code,message,"
    "kinetic_energy,"
    "max_stretch,mean_stretch,max_penetration,min_clearance,projected_area,drape_coefficient,drape_"
    "nodes,"
    "settle_time,rest_jitter,ms_per_step,wall_seconds_per_simulated_second,run_folder\n"
    "0,10,\"[5, "
    "5]\",ours,spring_damper,ok,0,\"\",0.01,0.2,0.05,0.001,-0.001,0.1,,,0.5,0.01,0.01,0.02,runs/"
    "000\n"
    "0,10,\"[5, "
    "5]\",other,spring_damper,ok,0,\"\",0.01,0.21,0.05,0.001,-0.001,0.1,,,0.6,0.01,0.02,0.03,runs/"
    "000\n"
    "1,10,\"[9, "
    "9]\",ours,spring_damper,ok,0,\"\",0.01,0.15,0.05,0.002,-0.002,0.1,,,0.5,0.01,0.01,0.05,runs/"
    "001\n"
    "1,10,\"[9, "
    "9]\",other,spring_damper,ok,0,\"\",0.01,0.16,0.05,0.002,-0.002,0.1,,,,0.01,0.02,0.06,runs/"
    "001\n"
    "2,10000,\"[5, 5]\",ours,spring_damper,unstable,1,\"solver 'ours' unstable: particle 3, step "
    "8\","
    ",,,,,,,,,,,,runs/002\n"
    "2,10000,\"[5, "
    "5]\",other,spring_damper,ok,1,\"\",0.01,0.001,0.0005,0.001,-0.001,0.1,,,0.4,0.01,0.02,0.03,"
    "runs/002\n"
    "3,10000,\"[9, "
    "9]\",ours,spring_damper,ok,0,\"\",0.01,0.002,0.0005,0.001,-0.001,0.1,,,0.3,0.01,0.01,0.05,"
    "runs/003\n"
    "3,10000,\"[9, "
    "9]\",other,spring_damper,ok,0,\"\",0.01,0.003,0.0005,0.001,-0.001,0.1,,,0.3,0.01,0.02,0.06,"
    "runs/003\n";
const std::string kSweepJson =
    "{\"command\": \"drapelab sweep s.yaml --vary cloth.springs.stretch.ks=10,10000 --vary "
    "cloth.resolution=[5,5],[9,9] --out s\", \"scene\": \"small\", \"varied\": ["
    "{\"key\": \"cloth.springs.stretch.ks\", \"values\": [\"10\", \"10000\"]},"
    "{\"key\": \"cloth.resolution\", \"values\": [\"[5, 5]\", \"[9, 9]\"]}]}\n";

TEST_F(ReportCli, SweepReportPlotsEveryMetricAgainstEveryVariedKey) {
  const fs::path sweep = dir() / "sweep";
  fs::create_directories(sweep);
  write_text(sweep / "sweep.csv", kSweepCsv);
  write_text(sweep / "sweep.json", kSweepJson);
  const auto result = run_drapelab({"report", sweep.string()});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::string html = read_text(sweep / "report.html");
  Page page(html);
  ASSERT_TRUE(page.well_formed()) << page.error();
  expect_references_inside(page.root(), sweep / "report.html", sweep);
  EXPECT_NE(html.find("particle 3, step 8"), std::string::npos)
      << "the quoted message, comma included";

  // The table: one row per CSV row.
  const auto tables = find(page.root(), "table");
  ASSERT_EQ(tables.size(), 1u);
  EXPECT_EQ(find(tables[0], "tr").size(), 1u + 8u);

  // No drape coefficient in the sweep, so four metrics against each of the two keys.
  const auto plots = plots_of(page, false);
  ASSERT_EQ(plots.size(), 8u);
  std::set<std::string> titles;
  for (const auto& plot : plots) titles.insert(plot.title);
  for (const std::string metric : {"Max stretch", "Max penetration", "Settle time", "Cost"})
    for (const std::string key : {"ks", "resolution"})
      EXPECT_EQ(titles.count(metric + " against " + key), 1u) << metric << " against " << key;
  bool failed_marked = false;
  for (const auto& plot : plots) {
    for (const std::string solver : {"ours", "other"}) {
      bool named = false;
      for (const auto& label : plot.legend) named = named || label.rfind(solver + " (", 0) == 0;
      EXPECT_TRUE(named) << plot.title << " legend lacks " << solver;
    }
    std::vector<std::string> x_labels;
    for (xmlNode* label : find(find(plot.svg, "g", "x-axis")[0], "text", "tick-label"))
      x_labels.push_back(text_of(label));
    if (plot.title.find("against ks") != std::string::npos) {
      // 10 to 10000 spans a factor 1000: decades on a log axis.
      EXPECT_EQ(x_labels, (std::vector<std::string>{"10", "100", "1000", "10000"})) << plot.title;
    } else {
      EXPECT_EQ(x_labels, (std::vector<std::string>{"[5, 5]", "[9, 9]"})) << plot.title;
    }
    failed_marked = failed_marked || !find(plot.svg, "path", "failed-marker").empty();
  }
  EXPECT_TRUE(failed_marked) << "the unstable run is marked";
}

TEST_F(ReportCli, AFolderThatIsNeitherExitsTwoNamingWhatIsMissing) {
  auto result = run_drapelab({"report", (dir() / "nowhere").string()});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("is not a folder"), std::string::npos) << result.output;

  result = run_drapelab({"report", dir().string()});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  for (const char* name : {"summary.json", "metrics.csv", "scene.yaml", "sweep.csv"})
    EXPECT_NE(result.output.find(name), std::string::npos) << name << " in: " << result.output;

  write_text(dir() / "metrics.csv", "solver,frame,time\n");
  result = run_drapelab({"report", dir().string()});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("missing summary.json and scene.yaml"), std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(dir() / "report.html"));
}

// ---- the page in a browser ------------------------------------------------------------------

const char* const kChromium = "/usr/bin/chromium";

struct Screenshot {
  int exit_code = -1;
  std::string log;  // Chromium's stderr
  fs::path png;
};

// Opens a page headless, screenshots it, and keeps the log (console messages go to stderr).
Screenshot screenshot(const fs::path& page, const fs::path& work) {
  Screenshot shot;
  shot.png = work / (page.stem().string() + "_screenshot.png");
  const fs::path log = work / (page.stem().string() + "_chromium.log");
  const std::string command =
      "timeout 60 " + drapelab::fixtures::shell_quote(kChromium) +
      " --headless --no-sandbox --disable-gpu --user-data-dir=" +
      drapelab::fixtures::shell_quote((work / "chromium_profile").string()) +
      " --screenshot=" + drapelab::fixtures::shell_quote(shot.png.string()) +
      " --window-size=1200,2400 --enable-logging=stderr --v=0 " +
      drapelab::fixtures::shell_quote("file://" + fs::absolute(page).string()) + " >/dev/null 2>" +
      drapelab::fixtures::shell_quote(log.string());
  const int status = std::system(command.c_str());
  shot.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  shot.log = fs::exists(log) ? read_text(log) : "";
  return shot;
}

// Console lines: anything the page's scripts printed, uncaught exceptions, failed resource loads.
std::vector<std::string> console_errors(const std::string& log) {
  std::vector<std::string> errors;
  for (const auto& line : drapelab::fixtures::split_lines(log))
    if (line.find("CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos)
      errors.push_back(line);
  return errors;
}

TEST_F(ReportCli, ChromiumShowsTheReportWithoutConsoleErrors) {
  ASSERT_TRUE(fs::exists(kChromium))
      << kChromium
      << " is missing: run tools/install-deps.sh (it installs chromium, "
         "which this test needs to open the report)";
  const fs::path run = make_run();
  fs::create_directories(run / "render");
  write_gradient_png(run / "render" / "frame_0012.png", 320, 160);
  ASSERT_EQ(run_drapelab({"report", run.string()}).exit_code, 0);

  const Screenshot shot = screenshot(run / "report.html", dir());
  ASSERT_EQ(shot.exit_code, 0) << shot.log;
  ASSERT_TRUE(fs::exists(shot.png)) << shot.log;
  // A blank page is one colour; the report has text, lines in several colours and the gradient.
  EXPECT_GT(distinct_colours(shot.png), 200) << shot.png;
  const auto errors = console_errors(shot.log);
  EXPECT_TRUE(errors.empty()) << errors.size() << " console line(s), the first: "
                              << (errors.empty() ? "" : errors[0]);

  // The checks can fail: a page with a script error is caught, a blank page is blank.
  write_text(
      dir() / "broken.html",
      "<!DOCTYPE html><html><body><p>x</p><script>no_such_function();</script></body></html>");
  const Screenshot broken = screenshot(dir() / "broken.html", dir());
  EXPECT_FALSE(console_errors(broken.log).empty()) << broken.log;
  write_text(dir() / "blank.html", "<!DOCTYPE html><html><body></body></html>");
  const Screenshot blank = screenshot(dir() / "blank.html", dir());
  ASSERT_TRUE(fs::exists(blank.png)) << blank.log;
  EXPECT_LT(distinct_colours(blank.png), 5);
}

// ---- the parts on their own -------------------------------------------------------------------

TEST(ReportParts, CsvReadsQuotedCellsAndEmptyCellsAsNaN) {
  const auto table = drapelab::run_folder::parse_csv("a,b,c\r\n1,\"x, \"\"y\"\"\",\n\n2.5,z\n");
  ASSERT_EQ(table.header, (std::vector<std::string>{"a", "b", "c"}));
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.rows[0][1], "x, \"y\"");
  EXPECT_TRUE(std::isnan(table.number(0, table.column("c"))));
  EXPECT_TRUE(std::isnan(table.number(1, table.column("c"))));  // a short row is padded
  EXPECT_EQ(table.number(1, table.column("a")), 2.5);
  EXPECT_TRUE(std::isnan(table.number(0, table.column("missing"))));
  EXPECT_FALSE(drapelab::run_folder::parse_number("1.5x").has_value());
  EXPECT_EQ(*drapelab::run_folder::parse_number(" +1e-3 "), 1e-3);
}

TEST(ReportParts, TicksAreNiceAndCoverTheData) {
  const auto axis = drapelab::report::linear_ticks(0.013, 0.987, 5);
  EXPECT_EQ(axis.lo, 0.0);
  EXPECT_DOUBLE_EQ(axis.hi, 1.0);
  EXPECT_EQ(axis.labels, (std::vector<std::string>{"0", "0.2", "0.4", "0.6", "0.8", "1"}));
  const auto hundreds = drapelab::report::linear_ticks(0.0, 1000.0, 5);
  EXPECT_EQ(hundreds.labels.at(1), "200") << "not 2e2";
  const auto small = drapelab::report::linear_ticks(-2e-5, 3e-5, 5);
  EXPECT_LE(small.lo, -2e-5);
  EXPECT_GE(small.hi, 3e-5);
  EXPECT_TRUE(contains(small.labels, "1e-5")) << "exponents written plainly";
  const auto flat = drapelab::report::linear_ticks(2.0, 2.0, 5);
  EXPECT_LT(flat.lo, 2.0);
  EXPECT_GT(flat.hi, 2.0);
  const auto decades = drapelab::report::log_ticks(3.0, 4000.0);
  EXPECT_EQ(decades.labels, (std::vector<std::string>{"1", "10", "100", "1000", "10000"}));
  EXPECT_EQ(drapelab::report::log_ticks(1.0, 50.0).labels,
            (std::vector<std::string>{"1", "2", "5", "10", "20", "50", "100"}));
}

TEST(ReportParts, Base64MatchesTheStandardVectors) {
  using drapelab::report::base64_encode;
  EXPECT_EQ(base64_encode(""), "");
  EXPECT_EQ(base64_encode("f"), "Zg==");
  EXPECT_EQ(base64_encode("fo"), "Zm8=");
  EXPECT_EQ(base64_encode("foo"), "Zm9v");
  EXPECT_EQ(base64_encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64_encode(std::string("\xff\x00\x10", 3)), "/wAQ");
}

TEST(ReportParts, SvgBreaksLinesAtMissingValuesAndMarksStoppedSolvers) {
  drapelab::report::Plot plot;
  plot.title = "t <&> \"q\"";
  plot.x_title = "time (s)";
  plot.y_title = "y (m)";
  const double nan = std::nan("");
  plot.series.push_back({"a", "#123456", "", {0, 1, 2, 3, 4}, {1, 2, nan, 3, 4}, {}, true, false});
  plot.series.push_back({"b", "#654321", "", {0, 1}, {nan, nan}, {}, false, false});
  const std::string svg = drapelab::report::svg_plot(plot, true);
  Page page(svg);
  ASSERT_TRUE(page.well_formed()) << page.error() << "\n" << svg;
  const auto info = inspect_plot(page.root());
  EXPECT_EQ(info.title, "t <&> \"q\"");
  EXPECT_EQ(find(page.root(), "polyline").size(), 2u) << "two pieces around the NaN";
  EXPECT_EQ(find(page.root(), "rect", "stop-marker").size(), 2u) << "on the line and in the legend";
  EXPECT_TRUE(contains(info.legend, "b")) << "a series with no value still has its legend entry";
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos)
      << "a standalone file";
}

}  // namespace

namespace {

// Sets summary.json's run state ("finished" in a whole run) to `state`.
void set_run_state(const fs::path& run, const std::string& state) {
  std::string summary = drapelab::fixtures::read_text(run / "summary.json");
  summary.replace(summary.find("\"finished\""), 10, "\"" + state + "\"");
  drapelab::fixtures::write_text(run / "summary.json", summary);
}

// Keeps the header and the rows of metrics.csv up to frame `last`, then half of the next row.
void cut_metrics_after(const fs::path& run, int last) {
  const auto lines =
      drapelab::fixtures::split_lines(drapelab::fixtures::read_text(run / "metrics.csv"));
  std::string text = lines[0] + "\n";
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const int frame = std::stoi(drapelab::fixtures::split_csv(lines[k])[1]);
    if (frame <= last) {
      text += lines[k] + "\n";
    } else {
      text += lines[k].substr(0, lines[k].size() / 2);  // cut mid-row, no newline
      break;
    }
  }
  drapelab::fixtures::write_text(run / "metrics.csv", text);
}

TEST_F(ReportCli, AKilledRunWithACutMetricsFileIsReportedIncomplete) {
  const fs::path run = make_run();
  set_run_state(run, "running");
  cut_metrics_after(run, 5);
  const auto result = run_drapelab({"report", run.string()});
  EXPECT_EQ(result.exit_code, 1) << result.output;
  // On stderr: the state, the cut file, and the frames missing per solver.
  EXPECT_NE(result.output.find("warning: the run is incomplete"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("metrics.csv ends in the middle of a row"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("ours: frames 0-5 recorded"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("missing 6-"), std::string::npos) << result.output;
  // On the page too, and the page still parses.
  const std::string html = drapelab::fixtures::read_text(run / "report.html");
  EXPECT_NE(html.find("Incomplete run"), std::string::npos);
  EXPECT_NE(html.find("missing 6-"), std::string::npos);
}

TEST_F(ReportCli, AnInterruptedRunIsReportedWithItsMissingFrames) {
  const fs::path run = make_run();
  set_run_state(run, "interrupted");
  cut_metrics_after(run, 3);
  // Ctrl-C leaves whole rows: put the newline back.
  drapelab::fixtures::write_text(
      run / "metrics.csv",
      drapelab::report::whole_rows(drapelab::fixtures::read_text(run / "metrics.csv"), nullptr));
  const auto result = run_drapelab({"report", run.string()});
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("note: the run was interrupted"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("missing 4-"), std::string::npos) << result.output;
  EXPECT_NE(drapelab::fixtures::read_text(run / "report.html").find("Interrupted run"),
            std::string::npos);
}

}  // namespace
