#include "drapelab/report/html_page.hpp"

#include <cmath>
#include <cstdio>

#include "drapelab/report/axis_ticks.hpp"
#include "drapelab/report/svg_plot.hpp"

namespace drapelab::report {

std::string page_begin(const std::string& title) {
  // No external style sheet, font or script: the page opens from disk with no network.
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\n<title>" +
         escape_xml(title) +
         "</title>\n<style>\n"
         "body { font-family: 'DejaVu Sans', Arial, Helvetica, sans-serif; margin: 1.5em auto; "
         "max-width: 1340px;"
         " padding: 0 1em; color: #222; }\n"
         "h1 { font-size: 1.6em; } h2 { font-size: 1.25em; border-bottom: 1px solid #ccc; "
         "margin-top: 1.6em; }\n"
         "table { border-collapse: collapse; font-size: 0.85em; margin: 0.5em 0; }\n"
         "th, td { border: 1px solid #ccc; padding: 0.2em 0.5em; vertical-align: top; white-space: "
         "nowrap; }\n"
         ".table-wrap { overflow-x: auto; max-width: 100%; }\n"
         "th { background: #f2f2f2; text-align: left; }\n"
         "td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }\n"
         "td.wrap { white-space: normal; min-width: 16em; max-width: 40em; }\n"
         "pre { background: #f6f6f6; border: 1px solid #ddd; padding: 0.6em; overflow-x: auto; "
         "font-size: 0.85em; }\n"
         ".plots { display: flex; flex-wrap: wrap; gap: 12px; }\n"
         "figure { margin: 0.5em 0; } figcaption { font-size: 0.85em; color: #555; }\n"
         ".plots figure { width: 560px; }\n"  // the plots' width: long captions wrap, two plots fit
                                              // a row
         "img.still, video { max-width: 100%; border: 1px solid #ccc; }\n"
         ".swatch { display: inline-block; width: 0.9em; height: 0.9em; margin-right: 0.35em;"
         " vertical-align: -0.1em; border: 1px solid #555; }\n"
         ".note { color: #555; font-size: 0.9em; }\n"
         ".status-ok { color: #1a7f37; } .status-bad { color: #c62828; font-weight: bold; }\n"
         "</style>\n</head>\n<body>\n";
}

std::string page_end() { return "</body>\n</html>\n"; }

std::string html_table(const std::vector<std::string>& header,
                       const std::vector<std::vector<TableCell>>& rows) {
  std::string out = "<div class=\"table-wrap\">\n<table>\n<thead><tr>";
  for (const auto& h : header) out += "<th>" + escape_xml(h) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (const auto& cell : row)
      out += (cell.numeric ? "<td class=\"num\">"
              : cell.wrap  ? "<td class=\"wrap\">"
                           : "<td>") +
             cell.html + "</td>";
    out += "</tr>\n";
  }
  return out + "</tbody>\n</table>\n</div>\n";
}

std::string format_value(double value, int digits) {
  if (std::isnan(value)) return "\u2014";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return plain_exponent(buffer);
}

std::string base64_encode(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t k = 0;
  for (; k + 2 < bytes.size(); k += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[k]) << 16) |
                       (static_cast<unsigned char>(bytes[k + 1]) << 8) |
                       static_cast<unsigned char>(bytes[k + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (k < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[k]) << 16;
    if (k + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[k + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += k + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string color_swatch(const std::string& color) {
  return "<span class=\"swatch\" style=\"background: " + escape_xml(color) + "\"></span>";
}

}  // namespace drapelab::report
