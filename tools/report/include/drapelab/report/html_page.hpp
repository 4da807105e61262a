// Pieces of the report's HTML page: the page frame with its inline style sheet, tables, numbers as
// text and base64 for embedded images. The markup is polyglot (every element closed, void elements
// written <img .../>, only XML's five named entities), so the page also parses as XML.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace drapelab::report {

// "<!DOCTYPE html><html><head>...<body>" with the title and the style sheet; page_end closes it.
std::string page_begin(const std::string& title);
std::string page_end();

struct TableCell {
  std::string html;      // already escaped markup
  bool numeric = false;  // right-aligned
  bool wrap = false;     // may break across lines (messages); other cells keep to one line
};
// A table with a header row of plain text and cells of markup, scrolling sideways when too wide.
std::string html_table(const std::vector<std::string>& header,
                       const std::vector<std::vector<TableCell>>& rows);

// A number with `digits` significant digits (%g, exponent written plainly), or an em dash for NaN.
std::string format_value(double value, int digits = 4);

// Standard base64 (RFC 4648, with padding), for data: URIs.
std::string base64_encode(std::string_view bytes);

// A coloured square for a legend-like key in tables.
std::string color_swatch(const std::string& color);

}  // namespace drapelab::report
