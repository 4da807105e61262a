// drapelab report DIR [--out FILE]: one self-contained HTML page for a run folder or a sweep folder
// (the kind is found from the files in it). The page needs no network and references only files
// inside the folder.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <stdexcept>

#include "drapelab/report/report.hpp"
#include "drapelab/report/run_completeness.hpp"
#include "drapelab/run_folder/run_transaction.hpp"
#include "verbs.hpp"

namespace drapelab::cli {

namespace fs = std::filesystem;

void add_report_options(CLI::App& verb, ReportArguments& arguments) {
  verb.add_option("folder", arguments.folder,
                  "A run folder (drapelab run) or a sweep folder (drapelab sweep)")
      ->required();
  verb.add_option("--out,-o", arguments.out,
                  "The HTML file to write (default: FOLDER/report.html)");
  verb.footer(
      "Examples:\n"
      "  drapelab report out/sphere_drape\n"
      "  drapelab report out/stiffness-sweep --out stiffness.html\n"
      "A run folder needs summary.json, metrics.csv and scene.yaml (compare.csv, contacts.csv and "
      "render/ "
      "are used when present); a sweep folder needs sweep.csv (and uses sweep.json). Prints the "
      "report's "
      "path. Exit codes: 0 written (an interrupted run with a notice of its missing frames), 1 "
      "written, but the run is incomplete (killed: summary.json in state running, or a CSV cut "
      "mid-row; the page and stderr say which frames are missing), 2 not a run or sweep folder "
      "(the message names what is missing), a file that cannot be read, or a report that cannot "
      "be written.");
}

namespace {

int write_report(const ReportArguments& arguments) {
  const fs::path folder = arguments.folder;
  const report::FolderCheck check = report::inspect_folder(folder);
  if (!check.kind) {
    std::cerr << "error: " << check.problem << "\n";
    return kExitBadInput;
  }
  const fs::path out = arguments.out.empty() ? folder / "report.html" : fs::path(arguments.out);
  std::string html;
  try {
    html = *check.kind == report::FolderKind::run ? report::run_report_html(folder, out)
                                                  : report::sweep_report_html(folder);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitBadInput;
  }
  // Write beside the target and rename, so a reader never sees half a page.
  const fs::path partial = fs::path(out.string() + ".partial");
  {
    std::ofstream file(partial, std::ios::binary | std::ios::trunc);
    file << html;
    if (!file) {
      std::cerr << "error: cannot write " << out.string() << " (does its folder exist?)\n";
      std::error_code ec;
      fs::remove(partial, ec);
      return kExitBadInput;
    }
  }
  std::error_code ec;
  fs::rename(partial, out, ec);
  if (ec) {
    std::cerr << "error: cannot write " << out.string() << ": " << ec.message() << "\n";
    fs::remove(partial, ec);
    return kExitBadInput;
  }
  std::cout << out.string() << "\n";
  if (*check.kind != report::FolderKind::run) return 0;
  // A page inside the run folder is recorded in its manifest: the next run there replaces it.
  if (const auto problem = run_folder::add_to_manifest(folder, {out}))
    std::cerr << "warning: the report is not in the run folder's manifest: " << *problem << "\n";
  // A run that is not whole is said on stderr too, for whoever reads only the terminal.
  const report::RunCompleteness completeness = report::inspect_run(folder);
  for (const auto& line : completeness.notices())
    std::cerr << (completeness.incomplete() ? "warning: " : "note: ") << line << "\n";
  return completeness.incomplete() ? 1 : 0;
}

}  // namespace

int report_verb(const ReportArguments& arguments) {
  try {
    return write_report(arguments);
  } catch (const std::bad_alloc&) {
    std::cerr << "error: drapelab report ran out of memory\n";
    return 1;
  } catch (const std::exception& e) {  // a file of the folder that cannot be read or parsed
    std::cerr << "error: " << e.what() << "\n";
    return kExitBadInput;
  }
}

}  // namespace drapelab::cli
