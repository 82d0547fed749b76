// `rockcal diagnose FILE`: a diagnosis campaign from submission to verdict table and HTML page.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "api/client.hpp"
#include "api/client_http.hpp"
#include "api/status_text.hpp"
#include "engine/json_input.hpp"
#include "orchestrator/summary_reader.hpp"

namespace rockcal::api {
namespace {

using nlohmann::json;

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The request as the server takes it: kind filled in, a dataset file read and inlined.
json diagnosis_request(const std::string& file) {
  json request = parse_json_input(read_file(file));
  if (!request.is_object()) throw std::runtime_error(file + ": not a JSON object");
  if (!request.contains("kind")) request["kind"] = "diagnosis";
  if (request.contains("dataset_file")) {
    if (!request["dataset_file"].is_string()) throw std::runtime_error("dataset_file: not a path");
    std::filesystem::path path = request["dataset_file"].get<std::string>();
    if (path.is_relative()) path = std::filesystem::path(file).parent_path() / path;
    const std::string text = read_file(path);
    if (path.extension() == ".csv") {
      request["dataset_csv"] = text;
    } else {
      request["dataset"] = parse_json_input(text);
    }
    request.erase("dataset_file");
  }
  return request;
}

using summary::at;

std::string fmt(const json& v, const char* format = "%.4g") {
  if (!v.is_number()) return v.is_string() ? v.get<std::string>() : "-";
  return summary::printed(v.get<double>(), format);
}

}  // namespace

std::string diagnosis_text(const json& s) {
  std::ostringstream out;
  const json& v = at(s, "verdict");
  const json& p = at(v, "parameter");
  const json& c = at(v, "confidence");
  out << "Verdict: " << fmt(at(v, "label"));
  if (p.is_object()) out << " (" << fmt(at(p, "name")) << " = " << fmt(at(p, "value")) << ")";
  if (at(v, "gap_closure").is_number()) out << ", G = " << fmt(at(v, "gap_closure"), "%.2f");
  out << ", confidence " << fmt(at(c, "level")) << " (bootstrap "
      << fmt(at(at(c, "bootstrap"), "agreement"), "%.2f") << ", seeds "
      << fmt(at(c, "seeds_agreeing")) << "/" << fmt(at(c, "seeds_informative"))
      << (at(c, "seeds_identical").is_number() && at(c, "seeds_identical").get<int>() > 0
              ? ", " + fmt(at(c, "seeds_identical")) + " identical to the nominal runs"
              : "")
      << ")\n  " << fmt(at(v, "reason")) << "\n  F_r0 = " << fmt(at(v, "fr0"))
      << ", F_s0 = " << fmt(at(v, "fs0")) << "\n\n";
  char line[256];
  std::snprintf(line, sizeof line, "  %-22s %10s %10s\n", "rms ln(sim/lab)", "before", "after");
  out << line;
  for (const char* role : {"calibration", "held_out"}) {
    const json& g = at(at(v, "gap"), role);
    std::snprintf(line, sizeof line, "  %-22s %10s %10s\n", role,
                  fmt(at(g, "before"), "%.4f").c_str(), fmt(at(g, "after"), "%.4f").c_str());
    out << line;
  }
  const json& u = at(v, "runner_up");
  if (u.is_object()) {
    out << "Runner-up: " << fmt(at(u, "effect")) << ", G = " << fmt(at(u, "gap_closure"), "%.2f")
        << " (" << fmt(at(u, "basis")) << ")\n";
  }
  out << "\nWhere the gap lies (base model; * = beyond budget + lab uncertainty):\n";
  std::snprintf(line, sizeof line, "  %-14s %-9s %-15s %-11s %12s %12s %9s %8s %8s %9s\n",
                "observation", "test", "observable", "role", "lab", "base sim", "ln ratio",
                "budget", "lab unc", "after");
  out << line;
  for (const json& o : at(s, "observations")) {
    const json& b = at(o, "base");
    std::snprintf(
        line, sizeof line, "  %-14s %-9s %-15s %-11s %12s %12s %8s%s %8s %8s %9s\n",
        fmt(at(o, "id")).c_str(), fmt(at(o, "test")).c_str(), fmt(at(o, "observable")).c_str(),
        fmt(at(o, "role")).c_str(), fmt(at(o, "lab")).c_str(), fmt(at(b, "sim")).c_str(),
        fmt(at(b, "residual"), "%+.4f").c_str(), at(b, "significant") == true ? "*" : " ",
        fmt(at(o, "budget"), "%.4f").c_str(), fmt(at(o, "lab_uncertainty"), "%.4f").c_str(),
        fmt(at(at(o, "verdict"), "residual"), "%+.4f").c_str());
    out << line;
  }
  const json& runs = at(s, "runs");
  if (at(runs, "failed_values").is_number() && runs["failed_values"].get<int>() > 0) {
    out << "  " << fmt(at(runs, "failed_values"))
        << " values missing from the grids (first: " << fmt(at(runs, "first_error")) << ")\n";
  }
  const json& candidates = at(s, "candidates");
  if (candidates.is_array() && !candidates.empty()) {
    const json& bounds = at(at(candidates[0], "fit"), "on_bounds");
    if (bounds.is_array() && !bounds.empty()) {
      out << "  The base model's fit lies on the bounds (";
      for (std::size_t k = 0; k < bounds.size(); ++k) out << (k ? ", " : "") << fmt(bounds[k]);
      out << "): the data want strengths outside them (widen \"bounds\"; or the lab's UCT/BTT "
             "ratio is out of the base model's reach), or do not depend on that strength there\n";
    }
  }
  out << "\nCandidates (ranked by held-out gap closure G):\n";
  std::snprintf(line, sizeof line, "  %4s %-22s %-12s %-8s %8s %-10s %s\n", "rank", "effect",
                "identifiable", "fits cal", "G", "basis", "fitted parameter");
  out << line;
  std::vector<json> ranked;
  for (const json& k : at(s, "candidates")) {
    if (k["effect"].is_string()) ranked.push_back(k);
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const json& a, const json& b) {
    return a["rank"].get<int>() < b["rank"].get<int>();
  });
  for (const json& k : ranked) {
    const json& kp = at(k, "parameter");
    const std::string param =
        kp.is_object() ? fmt(at(kp, "name")) + " = " + fmt(at(kp, "value")) : "";
    auto yes_no = [&](const char* key) {
      return at(k, key).is_boolean() ? (k[key].get<bool>() ? "yes" : "no") : "-";
    };
    std::snprintf(line, sizeof line, "  %4s %-22s %-12s %-8s %8s %-10s %s\n",
                  fmt(at(k, "rank")).c_str(), k["effect"].get<std::string>().c_str(),
                  yes_no("identifiable"), yes_no("fits_calibration"),
                  fmt(at(at(k, "gap_closure"), "value"), "%.3f").c_str(),
                  fmt(at(at(k, "gap_closure"), "basis")).c_str(), param.c_str());
    out << line;
  }
  const json& r = at(s, "ratio");
  if (r.is_object()) {
    out << "\nUCT/BTT ratio: lab " << fmt(at(r, "lab"), "%.3g") << ", the base model reaches "
        << fmt(at(r, "min"), "%.3g") << " to " << fmt(at(r, "max"), "%.3g") << " ("
        << (at(r, "inside") == true ? "inside" : "outside") << ")\n";
  }
  return out.str();
}

int client_diagnose(const ClientOptions& o, const std::string& file, const std::string& html_out) {
  const json request = diagnosis_request(file);
  Http http(o);
  auto posted =
      http.client.Post("/api/v1/campaigns", http.headers, request.dump(), "application/json");
  if (!posted || posted->status != 201) return http.report(posted);
  const std::int64_t id = json::parse(posted->body)["id"].get<std::int64_t>();
  const std::string path = "/api/v1/campaigns/" + std::to_string(id);
  std::cout << "diagnosis campaign " << id << std::endl;
  // The campaign's state follows its driver: it ends when the driver has (campaign_status.hpp).
  int exit_code = 0;
  const auto watched = http.watch(id, true, STDOUT_FILENO, exit_code);
  if (!watched) return exit_code;
  const json& c = *watched;
  std::cout << progress_line(c) << std::endl;
  if (c.value("driver_status", "") != "done") {
    std::cerr << "rockcal: diagnosis " << id << " did not finish: " << at(c, "summary").dump()
              << "\n";
    return 1;
  }
  std::cout << "\n" << diagnosis_text(c["summary"]);
  auto page = http.client.Get(path + "/report.html", http.headers);
  if (!page || page->status != 200) return http.report(page);
  const std::string out = html_out.empty() ? "diagnosis-" + std::to_string(id) + ".html" : html_out;
  std::ofstream(out) << page->body;
  std::cout << "\nreport: " << out << "\n";
  return 0;
}

}  // namespace rockcal::api
