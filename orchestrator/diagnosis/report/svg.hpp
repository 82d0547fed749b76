// Inline SVG charts for the HTML report: grouped bars and lines, no scripts, no external assets,
// so the page can be mailed or archived as one file.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace rockcal::diagnosis {

// &, <, >, " and ' escaped: every text of the page comes from a request or a dataset.
std::string escape_html(const std::string& text);

struct Series {
  std::string name;
  std::string color;           // CSS colour
  std::vector<double> values;  // one per category (bars) or per x = 0, 1, ... (lines); NaN: none
};

struct BarChart {
  std::string y_label;
  std::vector<std::string> categories;
  std::vector<Series> series;
  std::vector<double> band;  // per category: a grey band of +-band around 0 (empty: none)
  std::vector<std::pair<double, std::string>> lines;  // horizontal reference lines with labels
};

struct LineChart {
  std::string x_label;
  std::string y_label;
  std::vector<Series> series;
  bool log_y = false;  // non-positive values are dropped
};

// The charts carry no legend of their own (it would not fit eight candidates); this is one as HTML.
std::string legend_html(const std::vector<Series>& series);

std::string svg_bars(const BarChart& chart);
std::string svg_lines(const LineChart& chart);

}  // namespace rockcal::diagnosis
