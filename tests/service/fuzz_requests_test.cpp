// A bounded fuzz run over the request parsers: mutated campaign requests through the
// service's path (body text -> parse_json_input -> JobService::plan_campaign, every kind) and
// mutated job specs through the engine's (read_job, and json_text for what it prints). No input may
// crash or hang them, and every refusal must be the clean error the API turns into a 400
// (JsonInputError, RequestError) or the engine into exit 2 (JsonInputError, SpecError): anything
// else escaping fails the test with the input that caused it. An accepted job must survive its
// canonical round trip. ROCKCAL_FUZZ_SECONDS (per test, default 5) and ROCKCAL_FUZZ_SEED set the
// run, ROCKCAL_FUZZ_REPLAY=FILE checks one saved input; bench/fuzz_requests.sh runs it for longer.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <random>
#include <sstream>

#include "orchestrator/all_kinds.hpp"
#include "engine/job_file.hpp"
#include "engine/json_input.hpp"
#include "engine/spec.hpp"
#include "orchestrator/job_service.hpp"
#include "orchestrator/local_executor.hpp"
#include "orchestrator/request_error.hpp"
#include "support.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

double fuzz_seconds() {
  const char* env = std::getenv("ROCKCAL_FUZZ_SECONDS");
  return env ? std::max(0.1, std::atof(env)) : 5.0;
}
std::uint64_t fuzz_seed() {
  const char* env = std::getenv("ROCKCAL_FUZZ_SEED");
  return env ? std::strtoull(env, nullptr, 10) : 15;
}
// One input taking longer than this is a hang.
constexpr double kHangSeconds = 2.0;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

json example(const std::string& name) {
  return json::parse(read_text(fs::path(ROCKCAL_EXAMPLES) / name));
}

// A diagnosis request as `rockcal diagnose` sends it: its dataset file inlined.
json inlined(json request) {
  const fs::path file = fs::path(ROCKCAL_EXAMPLES) / request["dataset_file"].get<std::string>();
  request.erase("dataset_file");
  if (file.extension() == ".csv")
    request["dataset_csv"] = read_text(file);
  else
    request["dataset"] = json::parse(read_text(file));
  return request;
}

// Values that have broken parsers before: extremes, wrong types, odd text, deep nesting.
class Mutator {
 public:
  Mutator(std::uint64_t seed, const std::vector<std::string>& corpus) : g_(seed), corpus_(corpus) {
    for (const auto& text : corpus) collect_keys(json::parse(text));
  }

  std::string mutate(const std::string& seed) {
    std::string s = seed;
    const int rounds = 1 + static_cast<int>(g_() % 4);
    for (int i = 0; i < rounds; ++i) s = pick(3) == 0 ? mutate_bytes(s) : mutate_tree(s);
    return s;
  }

 private:
  std::size_t pick(std::size_t n) { return static_cast<std::size_t>(g_() % n); }

  void collect_keys(const json& j) {
    if (j.is_object()) {
      for (const auto& [k, v] : j.items()) {
        keys_.push_back(k);
        collect_keys(v);
      }
    } else if (j.is_array()) {
      for (const auto& v : j) collect_keys(v);
    }
  }

  json odd_value(int depth = 0) {
    static const std::vector<json> numbers = {0,
                                              -0.0,
                                              1,
                                              -1,
                                              2,
                                              3,
                                              0.5,
                                              1e-300,
                                              5e-324,
                                              1e300,
                                              1e308,
                                              -1e308,
                                              1e10,
                                              1e7,
                                              2e6,
                                              100000001,
                                              65,
                                              64,
                                              1.5,
                                              1e-9,
                                              4294967296,
                                              9223372036854775807LL,
                                              std::uint64_t(18446744073709551615ULL),
                                              -9223372036854775807LL - 1};
    static const std::vector<std::string> strings = {"",
                                                     "auto",
                                                     "fcc",
                                                     "random",
                                                     "uct",
                                                     "btt",
                                                     "sweep",
                                                     "calibration",
                                                     "diagnosis",
                                                     "lab",
                                                     "model",
                                                     "\xef\xbf\xbd",
                                                     std::string(1, '\0'),
                                                     std::string(300, 'x'),
                                                     "1e999",
                                                     "NaN",
                                                     "../../etc/passwd",
                                                     "heterogeneity",
                                                     "weibull_m"};
    switch (pick(depth > 3 ? 4 : 7)) {
      case 0:
      case 1:
        return numbers[pick(numbers.size())];
      case 2:
        return pick(2) ? json(strings[pick(strings.size())]) : json(keys_[pick(keys_.size())]);
      case 3:
        return pick(3) == 0 ? json(nullptr) : json(pick(2) == 0);
      case 4: {
        json a = json::array();
        for (std::size_t i = pick(6); i > 0; --i) a.push_back(odd_value(depth + 1));
        return a;
      }
      case 5: {
        json o = json::object();
        for (std::size_t i = pick(4); i > 0; --i)
          o[keys_[pick(keys_.size())]] = odd_value(depth + 1);
        return o;
      }
      default: {  // nesting around the limit (64) and beyond
        json v = 1;
        for (std::size_t i = 55 + pick(20); i > 0; --i)
          v = pick(2) ? json::array({v}) : json{{"a", v}};
        return v;
      }
    }
  }

  // Every node of the document, as pointers to it (bounded: documents are small).
  static void nodes(json& j, std::vector<json*>& out) {
    out.push_back(&j);
    if (j.is_structured())
      for (auto& v : j) nodes(v, out);
  }

  std::string mutate_tree(const std::string& text) {
    json doc = json::parse(text, nullptr, false);
    if (doc.is_discarded()) return mutate_bytes(text);
    std::vector<json*> all;
    nodes(doc, all);
    json& node = *all[pick(all.size())];
    switch (pick(5)) {
      case 0:
      case 1:
        node = odd_value();
        break;
      case 2:  // drop a member
        if (node.is_object() && !node.empty()) {
          auto it = node.begin();
          std::advance(it, static_cast<std::ptrdiff_t>(pick(node.size())));
          node.erase(it);
        } else if (node.is_array() && !node.empty()) {
          node.erase(pick(node.size()));
        }
        break;
      case 3:  // add one (known key elsewhere, or a twin)
        if (node.is_object())
          node[keys_[pick(keys_.size())]] = odd_value();
        else if (node.is_array())
          node.push_back(node.empty() ? odd_value() : node[pick(node.size())]);
        break;
      default:  // the same number a little off, or scaled far away
        if (node.is_number())
          node = node.get<double>() *
                 (pick(2) ? 1.0 + 1e-12 : std::pow(10.0, double(pick(600)) - 300.0));
        else
          node = odd_value();
    }
    return doc.dump();
  }

  std::string mutate_bytes(std::string s) {
    static const std::vector<std::string> tokens = {
        "{",       "}",     "[",   "]",        ",",      ":",    "\"",   "\\",       "\\u0000",
        "\\ud800", "1e999", "-",   "0",        "null",   "true", "\xff", "\xc0\x80", "\xed\xa0\x80",
        " ",       "\n",    "NaN", "Infinity", "{\"a\":"};
    switch (pick(6)) {
      case 0:
        if (!s.empty()) s[pick(s.size())] = static_cast<char>(pick(256));
        break;
      case 1:
        s.insert(pick(s.size() + 1), tokens[pick(tokens.size())]);
        break;
      case 2:
        if (!s.empty()) s.erase(pick(s.size()), 1 + pick(16));
        break;
      case 3:
        if (!s.empty()) {
          const std::size_t at = pick(s.size());
          s.insert(pick(s.size() + 1), s.substr(at, 1 + pick(32)));
        }
        break;
      case 4: {  // splice a piece of another input
        const std::string& other = corpus_[pick(corpus_.size())];
        const std::size_t at = pick(other.size());
        s.insert(pick(s.size() + 1), other.substr(at, 1 + pick(64)));
        break;
      }
      default:
        s.insert(pick(s.size() + 1), std::string(1 + pick(100), "[{"[pick(2)]));
    }
    return s;
  }

  std::mt19937_64 g_;
  const std::vector<std::string>& corpus_;
  std::vector<std::string> keys_;
};

struct Tally {
  long inputs = 0, accepted = 0, refused = 0, failures = 0;
  double slowest = 0;
};

// Keeps a failing input for a rerun: its path goes into the failure message.
std::string saved(const std::string& input) {
  const fs::path file = fs::temp_directory_path() / "rockcal-fuzz-failure.json";
  std::ofstream(file, std::ios::binary) << input;
  return file.string();
}

// Feeds mutated inputs to `check` (true: accepted, false: refused cleanly; anything thrown is a
// failure) until the time is up; fails on an input slower than kHangSeconds.
Tally fuzz(const std::vector<std::string>& corpus, std::uint64_t seed,
           const std::function<bool(const std::string&)>& check) {
  Mutator m(seed, corpus);
  std::mt19937_64 pick(seed + 1);
  Tally t;
  const char* replay = std::getenv("ROCKCAL_FUZZ_REPLAY");  // one saved input instead
  const auto end = Clock::now() + std::chrono::duration<double>(fuzz_seconds());
  while (replay ? t.inputs == 0 : Clock::now() < end) {
    const std::string input = replay ? read_text(replay) : m.mutate(corpus[pick() % corpus.size()]);
    const auto t0 = Clock::now();
    bool ok = false;
    try {
      ok = check(input);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "unclean rejection (" << e.what() << ") of the input in " << saved(input);
      t.failures = 1;
      return t;
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    t.slowest = std::max(t.slowest, seconds);
    if (seconds > kHangSeconds) {
      ADD_FAILURE() << "hang: " << seconds << " s for the input in " << saved(input);
      t.failures = 1;
      return t;
    }
    ++t.inputs;
    ++(ok ? t.accepted : t.refused);
  }
  return t;
}

void report(const char* what, const Tally& t) {
  std::cout << "[fuzz] " << what << ": " << t.inputs << " inputs (" << t.accepted << " accepted, "
            << t.refused << " refused) in " << fuzz_seconds() << " s, seed " << fuzz_seed()
            << ", slowest " << t.slowest * 1000 << " ms; "
            << (t.failures ? "stopped at a failing input" : "0 crashes, 0 hangs") << std::endl;
}

TEST(FuzzRequests, CampaignRequestsAreAcceptedOrRefusedCleanly) {
  TempDir dir;
  orch::ServiceConfig cfg;
  cfg.db_path = dir.path() / "fuzz.db";
  cfg.limits.max_jobs_per_campaign = 1000;
  orch::LocalExecutorConfig exec;
  exec.engine = fake_engine();
  orch::JobService service(cfg, std::make_unique<orch::LocalExecutor>(exec));
  orch::add_all_kinds(service.kinds());
  std::vector<std::string> corpus = {
      sweep_request({"uct", "btt"}, {50, 80}, {60, 90}).dump(),
      example("calibrate_seed_lab.json").dump(),
      inlined(example("diagnose_seed_lab.json")).dump(),
      inlined(example("diagnose_zigong.json")).dump(),
  };
  json points = sweep_request({"triaxial"}, {50}, {60});
  points.erase("grid");
  points["points"] = {{40, 50}, {70, 90}};
  points["job"]["loading"]["confining_pressure"] = 1000;
  corpus.push_back(points.dump());
  const Tally t = fuzz(corpus, fuzz_seed(), [&](const std::string& text) {
    json request;
    try {
      request = parse_json_input(text);
    } catch (const JsonInputError&) {
      return false;  // 400 "(body)"
    }
    try {
      service.plan_campaign(request);
      (void)request.dump();  // stored as text when accepted
      return true;
    } catch (const orch::RequestError&) {
      return false;  // 400 naming the field
    }
  });
  EXPECT_GT(t.inputs, 100);
  EXPECT_GT(t.accepted, 0) << "mutations too destructive: nothing got through";
  report("campaign requests", t);
}

TEST(FuzzRequests, JobSpecsAreAcceptedOrRefusedCleanly) {
  std::vector<std::string> corpus;
  for (const char* name : {"uct_small.json", "btt_small.json", "elastic_small.json",
                           "triaxial_small.json", "uct_effects.json", "uct_paper_two_rate.json"}) {
    corpus.push_back(example(name).dump());
  }
  json random = example("uct_small.json");
  random["sample"]["packing"] = "random";
  random["output"] = {{"vtk", true}, {"vtk_frames", 20}, {"curve_points", 500}};
  corpus.push_back(random.dump());
  const Tally t = fuzz(corpus, fuzz_seed(), [&](const std::string& text) {
    std::istringstream in(text);
    const JobFile job = read_job(in);  // rockcal-dem's own reading
    if (!job.spec) {
      // What rockcal-dem prints before exit 2, through its own writer: it must be JSON whatever
      // bytes the message quotes.
      const json printed = json::parse(json_text(job.error));
      EXPECT_TRUE(printed.contains("error") && printed.contains("field")) << text;
      return false;
    }
    const json canonical = to_json(*job.spec);
    EXPECT_EQ(parse_job(canonical), *job.spec) << text;
    EXPECT_EQ(to_json(parse_job(canonical)), canonical) << text;
    return true;
  });
  EXPECT_GT(t.inputs, 100);
  EXPECT_GT(t.accepted, 0) << "mutations too destructive: nothing got through";
  report("job specs", t);
}

}  // namespace
}  // namespace rockcal::test
