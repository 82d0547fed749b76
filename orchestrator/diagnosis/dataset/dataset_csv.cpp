// The CSV form of a lab dataset. A CSV is turned into the JSON form and parsed by the JSON parser,
// so both forms obey exactly the same rules and name fields the same way; CSV errors add the line.
//
//   # name: seed lab case                 (directives: "# KEY: VALUE" with KEY one of name,
//   # units: lab                           units, note, source, origin, lab, model_scale; lab and
//   # lab: {"specimen": ..., ...}          model_scale take JSON; before the header only)
//   # model_scale: {"kr": 8000, ...}
//   # any other comment line is free text
//   id,test,diameter,height,thickness,confining_pressure,loading_rate,observable,value,uncertainty,role
//   uct-1,uct,,,,,,peak_load,311000,15550,calibration      (empty cell = absent)
#include <array>
#include <charconv>
#include <sstream>
#include <stdexcept>

#include "engine/json_input.hpp"
#include "orchestrator/diagnosis/dataset/dataset.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

constexpr std::array<const char*, 11> kColumns = {
    "id",           "test",       "diameter", "height",      "thickness", "confining_pressure",
    "loading_rate", "observable", "value",    "uncertainty", "role"};
constexpr std::array<const char*, 5> kConditionColumns = {"diameter", "height", "thickness",
                                                          "confining_pressure", "loading_rate"};
constexpr std::array<const char*, 7> kDirectives = {"name",   "units", "note",       "source",
                                                    "origin", "lab",   "model_scale"};

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return "";
  return std::string(s.substr(first, s.find_last_not_of(" \t\r") - first + 1));
}

std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(trim(std::string_view(line).substr(start, comma - start)));
    if (comma == std::string::npos) return cells;
    start = comma + 1;
  }
}

bool is_condition(const std::string& column) {
  for (const char* c : kConditionColumns)
    if (column == c) return true;
  return false;
}

// A numeric cell, whole; "nan" and "inf" parse and are then refused by the JSON rules.
json number_cell(const std::string& cell, const std::string& field) {
  double x = 0;
  const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), x);
  if (ec != std::errc() || end != cell.data() + cell.size()) {
    throw orch::RequestError(field, "'" + cell + "' is not a number");
  }
  return x;
}

struct Line {
  int number;
  std::string text;
};

// "# KEY: VALUE" with KEY a lower-case word; anything else after '#' is a free comment.
std::optional<std::pair<std::string, std::string>> directive(const std::string& line) {
  std::size_t i = 1;
  while (i < line.size() && line[i] == ' ') ++i;
  const std::size_t key_start = i;
  while (i < line.size() && ((line[i] >= 'a' && line[i] <= 'z') || line[i] == '_')) ++i;
  if (i == key_start || i >= line.size() || line[i] != ':') return std::nullopt;
  return std::pair{line.substr(key_start, i - key_start), trim(line.substr(i + 1))};
}

void apply_directive(json& root, const std::string& key, const std::string& value,
                     const std::string& where) {
  bool known = false;
  for (const char* d : kDirectives) known |= key == d;
  if (!known) throw orch::RequestError(key, where + ": unknown directive '# " + key + ":'");
  if (root.contains(key)) throw orch::RequestError(key, where + ": given twice");
  if (key == "lab" || key == "model_scale") {
    try {
      root[key] = parse_json_input(value);
    } catch (const JsonInputError& e) {
      throw orch::RequestError(key, where + ": not JSON (" + e.what() + ")");
    }
  } else {
    root[key] = value;
  }
}

json observation_json(const std::vector<std::string>& cells, const std::string& path) {
  json obs = json::object();
  json conditions = json::object();
  for (std::size_t c = 0; c < kColumns.size(); ++c) {
    const std::string column = kColumns[c];
    if (cells[c].empty()) continue;  // absent
    if (is_condition(column)) {
      conditions[column] = number_cell(cells[c], path + ".conditions." + column);
    } else if (column == "value" || column == "uncertainty") {
      obs[column] = number_cell(cells[c], path + "." + column);
    } else {
      obs[column] = cells[c];
    }
  }
  if (!conditions.empty()) obs["conditions"] = conditions;
  return obs;
}

std::string expected_header() {
  std::string h;
  for (const char* c : kColumns) h.append(h.empty() ? "" : ",").append(c);
  return h;
}

std::string number_text(double x) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
  return std::string(buffer.data(), end);
}

void check_cell_text(const std::string& text, const std::string& what) {
  if (text.find_first_of(",\n\r") != std::string::npos) {
    throw std::invalid_argument(what + " '" + text +
                                "' cannot be a CSV cell (comma or line break)");
  }
}

}  // namespace

Dataset parse_dataset_csv(const std::string& text) {
  json root = json::object();
  json observations = json::array();
  std::vector<int> line_of_observation;
  bool header_seen = false;
  std::istringstream in(text);
  int number = 0;
  for (std::string raw; std::getline(in, raw);) {
    ++number;
    const std::string line = trim(raw);
    const std::string where = "line " + std::to_string(number);
    if (line.empty()) continue;
    if (line[0] == '#') {
      if (const auto d = directive(line)) {
        if (header_seen)
          throw orch::RequestError(d->first, where + ": directives go before the header");
        apply_directive(root, d->first, d->second, where);
      }
      continue;
    }
    const std::vector<std::string> cells = split_cells(line);
    if (!header_seen) {
      if (cells != split_cells(expected_header())) {
        throw orch::RequestError("(header)", where + ": the header must be " + expected_header());
      }
      header_seen = true;
      continue;
    }
    const std::string path = "observations[" + std::to_string(observations.size()) + "]";
    if (cells.size() != kColumns.size()) {
      throw orch::RequestError(path, where + ": " + std::to_string(cells.size()) +
                                         " cells, the header has " +
                                         std::to_string(kColumns.size()));
    }
    observations.push_back(observation_json(cells, path));
    line_of_observation.push_back(number);
  }
  if (!header_seen)
    throw orch::RequestError("(header)", "missing; it must be " + expected_header());
  root["observations"] = observations;
  try {
    return parse_dataset_json(root);
  } catch (const orch::RequestError& e) {
    // Point at the row: "observations[3]..." is the 4th data row.
    const std::string prefix = "observations[";
    if (e.field.rfind(prefix, 0) != 0) throw;
    const std::size_t index = std::stoul(e.field.substr(prefix.size()));
    const std::string message = e.message;
    throw orch::RequestError(
        e.field, message + " (line " + std::to_string(line_of_observation.at(index)) + ")");
  }
}

std::string to_csv(const Dataset& d) {
  const json j = to_json(d);
  std::ostringstream out;
  for (const char* key : kDirectives) {
    if (!j.contains(key)) continue;
    const json& v = j[key];
    const std::string text = v.is_string() ? v.get<std::string>() : v.dump();
    if (text.find_first_of("\n\r") != std::string::npos) {
      throw std::invalid_argument(std::string(key) + " has a line break; a CSV directive cannot");
    }
    if (!text.empty()) out << "# " << key << ": " << text << "\n";
  }
  out << expected_header() << "\n";
  for (const json& o : j["observations"]) {
    std::vector<std::string> cells;
    const json conditions = o.value("conditions", json::object());
    for (const char* column : kColumns) {
      const json* v = is_condition(column)
                          ? (conditions.contains(column) ? &conditions[column] : nullptr)
                          : (o.contains(column) ? &o[column] : nullptr);
      if (!v) {
        cells.emplace_back();
      } else if (v->is_string()) {
        check_cell_text(v->get<std::string>(), column);
        cells.push_back(v->get<std::string>());
      } else {
        cells.push_back(number_text(v->get<double>()));
      }
    }
    for (std::size_t c = 0; c < cells.size(); ++c) out << (c ? "," : "") << cells[c];
    out << "\n";
  }
  return out.str();
}

}  // namespace rockcal::diagnosis
