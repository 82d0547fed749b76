#include "orchestrator/diagnosis/report/svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace rockcal::diagnosis {
namespace {

constexpr double kWidth = 760, kHeight = 330;
constexpr double kLeft = 64, kRight = 16, kTop = 12, kBottom = 96;

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

struct Scale {
  double lo, hi;
  double y(double v) const { return kTop + (hi - v) / (hi - lo) * (kHeight - kTop - kBottom); }
};

// Round-ish tick values covering [lo, hi].
std::vector<double> ticks(double lo, double hi) {
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / 5;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  }
  std::vector<double> out;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) out.push_back(t);
  return out;
}

// 1, 2, 5 x 10^k inside [10^lo, 10^hi], as log10 values; decades only when there are many.
std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> out;
  const bool decades = hi - lo > 3;
  for (double k = std::floor(lo); k <= std::ceil(hi); k += 1) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double t = k + std::log10(m);
      if (t >= lo - 1e-9 && t <= hi + 1e-9 && (!decades || m == 1.0)) out.push_back(t);
    }
  }
  return out.empty() ? ticks(lo, hi) : out;
}

void frame(std::ostringstream& out, const Scale& s, const std::string& y_label,
           const std::vector<double>& tick_values, bool log_labels) {
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << kWidth << " " << kHeight
      << "\" width=\"" << kWidth << "\" height=\"" << kHeight
      << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  for (double t : tick_values) {
    out << "<line x1=\"" << kLeft << "\" x2=\"" << kWidth - kRight << "\" y1=\"" << s.y(t)
        << "\" y2=\"" << s.y(t) << "\" stroke=\"#ddd\"/>";
    out << "<text x=\"" << kLeft - 4 << "\" y=\"" << s.y(t) + 4 << "\" text-anchor=\"end\">"
        << fmt(log_labels ? std::pow(10.0, t) : t) << "</text>\n";
  }
  out << "<line x1=\"" << kLeft << "\" x2=\"" << kLeft << "\" y1=\"" << kTop << "\" y2=\""
      << kHeight - kBottom << "\" stroke=\"#333\"/>\n";
  out << "<text transform=\"translate(14," << (kTop + kHeight - kBottom) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << escape_html(y_label) << "</text>\n";
}

}  // namespace

std::string escape_html(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string legend_html(const std::vector<Series>& series) {
  std::string out = "<p class=\"legend\">";
  for (const Series& s : series) {
    out += "<span><i style=\"background:" + s.color + "\"></i>" + escape_html(s.name) + "</span> ";
  }
  return out + "</p>\n";
}

std::string svg_bars(const BarChart& c) {
  double lo = 0, hi = 0;
  for (const Series& s : c.series) {
    for (double v : s.values) {
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    }
  }
  for (double b : c.band) {
    if (std::isfinite(b)) lo = std::min(lo, -b), hi = std::max(hi, b);
  }
  for (const auto& [y, label] : c.lines) lo = std::min(lo, y), hi = std::max(hi, y);
  if (hi - lo < 1e-12) hi = lo + 1;
  const double pad = 0.08 * (hi - lo);
  const Scale s{lo - (lo < 0 ? pad : 0), hi + pad};
  std::ostringstream out;
  frame(out, s, c.y_label, ticks(s.lo, s.hi), false);
  const std::size_t n = c.categories.size();
  const double slot = (kWidth - kLeft - kRight) / double(std::max<std::size_t>(n, 1));
  for (std::size_t k = 0; k < n; ++k) {
    // Only the series with a value here share the slot, so a lone bar is centred.
    std::vector<std::size_t> present;
    for (std::size_t j = 0; j < c.series.size(); ++j) {
      if (k < c.series[j].values.size() && std::isfinite(c.series[j].values[k]))
        present.push_back(j);
    }
    const double bar = 0.8 * slot / double(std::max<std::size_t>(present.size(), 1));
    const double x0 = kLeft + k * slot;
    if (k < c.band.size() && std::isfinite(c.band[k])) {
      out << "<rect x=\"" << x0 + 0.05 * slot << "\" y=\"" << s.y(c.band[k]) << "\" width=\""
          << 0.9 * slot << "\" height=\"" << s.y(-c.band[k]) - s.y(c.band[k])
          << "\" fill=\"#eee\"/>";
    }
    for (std::size_t m = 0; m < present.size(); ++m) {
      const std::size_t j = present[m];
      const double v = c.series[j].values[k];
      const double top = s.y(std::max(v, 0.0)), bottom = s.y(std::min(v, 0.0));
      out << "<rect x=\"" << x0 + 0.1 * slot + m * bar << "\" y=\"" << top << "\" width=\"" << bar
          << "\" height=\"" << std::max(bottom - top, 0.5) << "\" fill=\"" << c.series[j].color
          << "\"><title>" << escape_html(c.categories[k]) << " " << escape_html(c.series[j].name)
          << ": " << fmt(v) << "</title></rect>";
    }
    const double xl = x0 + 0.5 * slot, yl = kHeight - kBottom + 12;
    out << "<text transform=\"translate(" << xl << "," << yl
        << ") rotate(-35)\" text-anchor=\"end\">" << escape_html(c.categories[k]) << "</text>\n";
  }
  out << "<line x1=\"" << kLeft << "\" x2=\"" << kWidth - kRight << "\" y1=\"" << s.y(0)
      << "\" y2=\"" << s.y(0) << "\" stroke=\"#333\"/>\n";
  for (const auto& [y, label] : c.lines) {
    out << "<line x1=\"" << kLeft << "\" x2=\"" << kWidth - kRight << "\" y1=\"" << s.y(y)
        << "\" y2=\"" << s.y(y) << "\" stroke=\"#c00\" stroke-dasharray=\"5,4\"/><text x=\""
        << kWidth - kRight << "\" y=\"" << s.y(y) - 4 << "\" text-anchor=\"end\" fill=\"#c00\">"
        << escape_html(label) << "</text>\n";
  }
  out << "</svg>\n";
  return out.str();
}

std::string svg_lines(const LineChart& c) {
  auto tr = [&](double v) { return c.log_y ? (v > 0 ? std::log10(v) : NAN) : v; };
  double lo = INFINITY, hi = -INFINITY;
  std::size_t longest = 1;
  for (const Series& s : c.series) {
    longest = std::max(longest, s.values.size());
    for (double v : s.values) {
      const double t = tr(v);
      if (std::isfinite(t)) lo = std::min(lo, t), hi = std::max(hi, t);
    }
  }
  if (!std::isfinite(lo)) lo = 0, hi = 1;
  if (hi - lo < 1e-12) hi = lo + 1;
  const Scale s{lo, hi};
  std::ostringstream out;
  frame(out, s, c.y_label, c.log_y ? log_ticks(lo, hi) : ticks(lo, hi), c.log_y);
  const double span = kWidth - kLeft - kRight;
  auto x_of = [&](std::size_t i) {
    return kLeft + span * double(i) / double(std::max<std::size_t>(longest - 1, 1));
  };
  for (const Series& series : c.series) {
    std::string points;
    for (std::size_t i = 0; i < series.values.size(); ++i) {
      const double t = tr(series.values[i]);
      if (std::isfinite(t)) points += fmt(x_of(i)) + "," + fmt(s.y(t)) + " ";
    }
    out << "<polyline fill=\"none\" stroke-width=\"1.6\" stroke=\"" << series.color
        << "\" points=\"" << points << "\"><title>" << escape_html(series.name)
        << "</title></polyline>\n";
  }
  for (double t : ticks(0, double(longest - 1))) {
    out << "<text x=\"" << x_of(std::size_t(t)) << "\" y=\"" << kHeight - kBottom + 14
        << "\" text-anchor=\"middle\">" << fmt(t) << "</text>";
  }
  out << "<text x=\"" << kLeft + span / 2 << "\" y=\"" << kHeight - kBottom + 32
      << "\" text-anchor=\"middle\">" << escape_html(c.x_label) << "</text>\n";
  out << "</svg>\n";
  return out.str();
}

}  // namespace rockcal::diagnosis
