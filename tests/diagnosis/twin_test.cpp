// The synthetic twin: its design for a template, the seeded truth and noise (with a formula
// standing in for the engine), and the real thing: rockcal-dem runs on a tiny sample, through the
// "twin" campaign kind on a service of its own and through `rockcal twin`.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "engine_service.hpp"
#include "orchestrator/diagnosis/twin/twin.hpp"
#include "orchestrator/diagnosis/twin/twin_design.hpp"
#include "orchestrator/diagnosis/twin/twin_kind.hpp"

namespace rockcal::diagnosis {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A formula engine: loads grow with the bond strengths and the specimen, so the twin's
// bookkeeping can be checked without physics.
json formula_result(const json& job) {
  const double fr0 = job["bond"]["fr0"], fs0 = job["bond"]["fs0"];
  const double d = job["sample"]["diameter"];
  const double p = job["loading"].value("confining_pressure", 0.0);
  const double load = std::sqrt(fr0 * fs0) * d * d + 5 * p * d * d;
  const bool axial = job["test"] != "btt";
  return {{"test", job["test"]},
          {"peak_load", load},
          {"strength", load / (M_PI * d * d / 4)},
          {"youngs_modulus", 1000.0},
          {"peak_strain", axial ? json(0.01 * std::sqrt(fr0 / fs0)) : json(nullptr)},
          {"peak_reached", true},
          {"engine_version", "formula"}};
}

RunJobs formula_engine(std::vector<json>* seen = nullptr) {
  return [seen](const std::vector<json>& jobs) {
    std::vector<json> results;
    for (const json& job : jobs) {
      if (seen) seen->push_back(job);
      results.push_back(formula_result(job));
    }
    return results;
  };
}

const Observation& find(const std::vector<Observation>& list, const std::string& id) {
  for (const Observation& o : list)
    if (o.id == id) return o;
  throw std::runtime_error("no observation " + id);
}

TEST(DiagnosisTwin, DesignFollowsTheTemplate) {
  json t = demo_twin_template();
  t["sample"]["thickness"] = 3;
  std::vector<json> jobs;
  const TwinDesign d = make_twin_design(t, formula_engine(&jobs));
  ASSERT_EQ(jobs.size(), 1u);  // the base UCT, at the engine's default bond strengths
  EXPECT_EQ(jobs[0]["test"], "uct");
  EXPECT_EQ(jobs[0]["bond"]["fr0"], 64.0);
  EXPECT_FALSE(jobs[0].contains("effects"));
  EXPECT_DOUBLE_EQ(d.base_ucs_pa, formula_result(jobs[0])["strength"].get<double>());
  EXPECT_DOUBLE_EQ(d.p_low_pa, round_to_two_digits(0.1 * d.base_ucs_pa));
  EXPECT_DOUBLE_EQ(d.p_high_pa, round_to_two_digits(0.3 * d.base_ucs_pa));
  EXPECT_DOUBLE_EQ(round_to_two_digits(48.55), 49);
  EXPECT_DOUBLE_EQ(round_to_two_digits(0.014563), 0.015);

  ASSERT_EQ(d.observations.size(), 10u);
  const auto& o = d.observations;
  const auto role = [&](const std::string& id) { return find(o, id).role; };
  for (const char* id : {"uct-peak", "uct-modulus", "btt-peak", "tri-low", "btt-fast"})
    EXPECT_EQ(role(id), Role::calibration) << id;
  for (const char* id : {"tri-high", "uct-squat", "btt-large", "uct-fast", "uct-peak-strain"})
    EXPECT_EQ(role(id), Role::held_out) << id;
  EXPECT_EQ(find(o, "uct-modulus").observable, Observable::youngs_modulus);
  EXPECT_EQ(find(o, "tri-low").test, TestKind::triaxial);
  EXPECT_EQ(find(o, "tri-low").conditions.confining_pressure_pa, d.p_low_pa);
  EXPECT_EQ(find(o, "tri-high").conditions.confining_pressure_pa, d.p_high_pa);
  EXPECT_EQ(*find(o, "uct-squat").conditions.diameter_m, 8);  // H/D = 1
  EXPECT_EQ(*find(o, "uct-squat").conditions.height_m, 8);
  EXPECT_EQ(*find(o, "btt-peak").conditions.thickness_m, 3);
  EXPECT_EQ(*find(o, "btt-large").conditions.thickness_m, 4.5);
  EXPECT_EQ(*find(o, "uct-fast").conditions.loading_rate_m_s, 0.2);
  EXPECT_EQ(*find(o, "btt-fast").conditions.loading_rate_m_s, 0.2);  // the disc of btt-peak
  EXPECT_EQ(*find(o, "btt-fast").conditions.thickness_m, 3);

  // A template's own bond strengths are the reference (and the centre of the truth draw).
  t["bond"] = {{"fr0", 100}, {"fs0", 50}};
  jobs.clear();
  EXPECT_EQ(make_twin_design(t, formula_engine(&jobs)).model.bond.fs0_n, 50);
  EXPECT_EQ(jobs[0]["bond"]["fr0"], 100.0);
}

TEST(DiagnosisTwin, BadTemplatesAndRequestsAreRefused) {
  const auto field = [](const json& t) {
    try {
      make_twin_design(t, formula_engine());
    } catch (const orch::RequestError& e) {
      return e.field;
    }
    return std::string();
  };
  json t = demo_twin_template();
  t["test"] = "uct";
  EXPECT_EQ(field(t), "job.test");
  t = demo_twin_template();
  t["effects"] = {{"rate", {}}};
  EXPECT_EQ(field(t), "job.effects");
  t = demo_twin_template();
  t["sample"]["diameter"] = -1;
  EXPECT_EQ(field(t), "job.sample.diameter");

  // A request no twin can be made of is refused naming the CLI's field, before any run.
  auto refusal = [](const TwinRequest& r) -> std::string {
    try {
      check_twin_request(r);
    } catch (const orch::RequestError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  EXPECT_EQ(
      refusal({"bogus", 1, 1, 0.02}).rfind("effect: unknown effect 'bogus' (known: none, ", 0), 0u);
  EXPECT_EQ(refusal({"rate", 100, 1, 0.02}), "value: must be in [0.125, 16.0] (rate.speed_factor)");
  EXPECT_EQ(twin_effects({"none", 0, 1, 0.02}), json::object());
  // In an FCC template the interaction range changes nothing below sqrt(2): such a twin would be
  // a null labelled with an effect, and is refused; in a random packing any factor above 1 bonds
  // more.
  JobSpec fcc;
  auto changes = [](const JobSpec& model, const TwinRequest& r) -> std::string {
    try {
      check_twin_value_changes_model(model, r);
    } catch (const orch::RequestError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  EXPECT_EQ(changes(fcc, {"interaction_range", 1.25, 1, 0.02}),
            "value: interaction_range.factor 1.25 leaves this template's model unchanged (it "
            "changes it from " +
                json(std::sqrt(2.0) * 1.01).dump() + " on)");
  EXPECT_EQ(changes(fcc, {"interaction_range", 1.45, 1, 0.02}), "(accepted)");
  EXPECT_EQ(changes(fcc, {"rate", 2, 1, 0.02}), "(accepted)");
  JobSpec random = fcc;
  random.sample.packing = "random";
  EXPECT_EQ(changes(random, {"interaction_range", 1.25, 1, 0.02}), "(accepted)");
  EXPECT_EQ(refusal({"none", 0, 1, 0.02, 3.0}), "(accepted)");
  const std::string resolution = "resolution: must be in [1, 3] (1 = the template's own)";
  EXPECT_EQ(refusal({"none", 0, 1, 0.02, 3.5}), resolution);
  EXPECT_EQ(refusal({"none", 0, 1, 0.02, 0.9}), resolution);
  EXPECT_EQ(refusal({"none", 0, 1, 0.0}),
            "noise: must be positive (the uncertainty is noise x value)");
  EXPECT_EQ(twin_effects({"heterogeneity", 3, 1, 0.02}),
            json({{"heterogeneity", {{"weibull_m", 3.0}}}}));
  const TwinDesign d = make_twin_design(demo_twin_template(), formula_engine());
  EXPECT_THROW(make_twin(d, {"none", 0, 1, 0.0}, formula_engine()), orch::RequestError);
}

// The "twin" campaign is refused before any run, naming the field as `rockcal twin` names it.
TEST(DiagnosisTwin, TwinCampaignsAreRefusedNamingTheField) {
  const auto refusal = [](const json& r) -> std::string {
    try {
      parse_twin_campaign(r);
    } catch (const orch::RequestError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  const json good = {{"kind", "twin"}, {"effect", "rate"}, {"value", 4}, {"seed", 2}};
  EXPECT_EQ(refusal(good), "(accepted)");
  EXPECT_EQ(parse_twin_campaign(good).job_template, demo_twin_template());
  EXPECT_EQ(refusal({{"kind", "twin"}}), "effect: is required (an effect or \"none\")");
  EXPECT_EQ(refusal({{"kind", "twin"}, {"effect", "rate"}}), "value: is required with effect rate");
  EXPECT_EQ(refusal({{"kind", "twin"}, {"effect", "none"}, {"colour", 1}}),
            "colour: unknown field");
  EXPECT_EQ(refusal({{"kind", "twin"}, {"effect", "none"}, {"seed", -1}}),
            "seed: must be in [0, 9223372036854775807]");
  EXPECT_EQ(refusal({{"kind", "twin"}, {"effect", "none"}, {"truth_seed", -2}}),
            "truth_seed: must be in [0, 9223372036854775807]");
  EXPECT_EQ(parse_twin_campaign({{"kind", "twin"}, {"effect", "none"}, {"truth_seed", 7}})
                .twin.truth_seed,
            std::optional<std::uint64_t>(7));
  EXPECT_EQ(refusal({{"kind", "twin"}, {"effect", "none"}, {"resolution", 4}}),
            "resolution: must be in [1, 3] (1 = the template's own)");
  json bad = good;
  bad["job"] = demo_twin_template();
  bad["job"]["sample"]["diameter"] = -1;
  EXPECT_EQ(refusal(bad).rfind("job.sample.diameter: ", 0), 0u) << refusal(bad);
}

TEST(DiagnosisTwin, TruthAndNoiseComeFromTheSeed) {
  const TwinDesign d = make_twin_design(demo_twin_template(), formula_engine());
  std::vector<json> jobs;
  const TwinRequest request{.effect = "heterogeneity", .value = 3, .seed = 11, .noise = 0.05};
  const Twin a = make_twin(d, request, formula_engine(&jobs));
  const Twin b = make_twin(d, request, formula_engine());
  EXPECT_EQ(to_json(a.dataset), to_json(b.dataset));
  EXPECT_EQ(a.truth, b.truth);
  const Twin other = make_twin(d, {"heterogeneity", 3, 12, 0.05}, formula_engine());
  EXPECT_NE(a.truth["fr0"], other.truth["fr0"]);

  // The UCT's peak, modulus and peak strain share a run: 8 distinct jobs, each with the hidden
  // effect, drawn with the twin's own seed (not the model's 1 or the budget's 2 and 3).
  EXPECT_EQ(jobs.size(), 8u);
  for (const json& job : jobs) {
    EXPECT_EQ(job["effects"]["heterogeneity"]["weibull_m"], 3.0);
    EXPECT_EQ(job["bond"]["fr0"], a.truth["fr0"]);
    EXPECT_EQ(job["sample"]["seed"], 1 + kTwinSeedOffset + 11);
    EXPECT_EQ(job["sample"]["radius"], 1.0);
  }
  EXPECT_EQ(a.dataset.origin, Origin::same_resolution_model);
  const TruthBonds truth = draw_truth_bonds(d.model, 11);
  EXPECT_EQ(a.truth["fr0"], truth.fr0_n);
  EXPECT_LE(std::abs(std::log(truth.fr0_n / 64)), 0.5);
  EXPECT_LE(std::abs(std::log(truth.fs0_n / truth.fr0_n)), 0.5);

  // Lab-like noise: value = noise-free x exp(noise N(0,1)), uncertainty = noise x value.
  ASSERT_EQ(a.truth["observations"].size(), a.dataset.observations.size());
  for (std::size_t i = 0; i < a.dataset.observations.size(); ++i) {
    const Observation& o = a.dataset.observations[i];
    const double clean = a.truth["observations"][i]["noise_free"];
    EXPECT_LT(std::abs(std::log(o.value / clean)), 5 * 0.05) << o.id;
    EXPECT_NE(o.value, clean) << o.id;
    EXPECT_DOUBLE_EQ(o.uncertainty, 0.05 * o.value) << o.id;
  }
  // The dataset does not give the effect away.
  const std::string dumped = to_json(a.dataset).dump() + to_csv(a.dataset);
  EXPECT_EQ(dumped.find("heterogeneity"), std::string::npos);
  EXPECT_EQ(dumped.find("weibull"), std::string::npos);
  EXPECT_EQ(a.truth["effect"], "heterogeneity");
  EXPECT_EQ(a.truth["parameter"], "weibull_m");
  EXPECT_EQ(truth_file_for("out/twin.json"), "out/twin.truth.json");
  EXPECT_EQ(truth_file_for("twin.csv"), "twin.truth.json");
}

// Focus: a truth seed. Twins of one truth seed hide the same bond strengths (a matrix of them
// shares the model's design runs), while their packings and lab noise still follow their own
// seed, exactly as without it.
TEST(DiagnosisTwin, ATruthSeedFixesTheTruthAndLeavesTheNoiseToTheSeed) {
  const TwinDesign d = make_twin_design(demo_twin_template(), formula_engine());
  TwinRequest first{"none", 0, 11, 0.05}, second{"none", 0, 12, 0.05};
  first.truth_seed = second.truth_seed = 5;
  std::vector<json> jobs_first, jobs_second;
  const Twin a = make_twin(d, first, formula_engine(&jobs_first));
  const Twin b = make_twin(d, second, formula_engine(&jobs_second));
  const TruthBonds truth = draw_truth_bonds(d.model, 5);
  EXPECT_EQ(a.truth["fr0"], truth.fr0_n);
  EXPECT_EQ(b.truth["fr0"], truth.fr0_n);
  EXPECT_EQ(b.truth["fs0"], truth.fs0_n);
  EXPECT_EQ(a.truth["truth_seed"], 5);
  EXPECT_EQ(jobs_first[0]["sample"]["seed"], 1 + kTwinSeedOffset + 11);
  EXPECT_EQ(jobs_second[0]["sample"]["seed"], 1 + kTwinSeedOffset + 12);
  // The noise is seed 11's with or without the truth seed: each observation's noise factor
  // (value over its noise-free value) is the same.
  const Twin plain = make_twin(d, {"none", 0, 11, 0.05}, formula_engine());
  EXPECT_TRUE(plain.truth["truth_seed"].is_null());
  ASSERT_EQ(plain.dataset.observations.size(), a.dataset.observations.size());
  for (std::size_t i = 0; i < a.dataset.observations.size(); ++i) {
    const double with =
        a.dataset.observations[i].value / a.truth["observations"][i]["noise_free"].get<double>();
    const double without = plain.dataset.observations[i].value /
                           plain.truth["observations"][i]["noise_free"].get<double>();
    EXPECT_NEAR(with, without, 1e-12) << a.dataset.observations[i].id;
  }
}

// Focus: a next test measured by the twin (the check that a diagnosis's next test names the hidden
// effect). It is read as the report states it, run at its own conditions with the twin's truth
// and effect, and added as a calibration observation; the design's observations keep their
// values, so the twin is the one without it plus that test. Bad next tests name their field.
TEST(DiagnosisTwin, ANextTestIsMeasuredTooAsACalibrationObservation) {
  const json slender = {
      {"id", "menu-uct-hd3"},
      {"test", "uct"},
      {"observable", "peak_load"},
      {"description", "the peak load of a slender UCT (H/D = 3)"},
      {"conditions",
       {{"units", "model"}, {"diameter", 8.0}, {"height", 24.0}, {"platen_velocity", 0.05}}}};
  const TwinDesign d = make_twin_design(demo_twin_template(), formula_engine());
  TwinRequest plain_request{"rate", 4, 11, 0.05};
  TwinRequest request = plain_request;
  request.next_tests = {parse_next_test(slender, "next_tests[0]")};
  std::vector<json> jobs;
  const Twin with = make_twin(d, request, formula_engine(&jobs));
  const Twin plain = make_twin(d, plain_request, formula_engine());
  ASSERT_EQ(with.dataset.observations.size(), plain.dataset.observations.size() + 1);
  for (std::size_t i = 0; i < plain.dataset.observations.size(); ++i) {
    EXPECT_EQ(with.dataset.observations[i].value, plain.dataset.observations[i].value);
  }
  const Observation& added = with.dataset.observations.back();
  EXPECT_EQ(added.id, "menu-uct-hd3");
  EXPECT_EQ(added.role, Role::calibration);
  EXPECT_EQ(added.conditions.height_m, 24.0);
  EXPECT_EQ(added.conditions.loading_rate_m_s, 0.05);
  const json& job = jobs.back();
  EXPECT_EQ(job["test"], "uct");
  EXPECT_EQ(job["sample"]["height"], 24.0);
  EXPECT_EQ(job["effects"]["rate"]["speed_factor"], 4.0);
  EXPECT_EQ(job["bond"]["fr0"], with.truth["fr0"]);
  const double clean = with.truth["observations"].back()["noise_free"];
  EXPECT_EQ(clean, formula_result(job)["peak_load"].get<double>());
  EXPECT_DOUBLE_EQ(added.uncertainty, 0.05 * added.value);

  const auto refusal = [](json tests) -> std::string {
    try {
      parse_twin_campaign({{"kind", "twin"}, {"effect", "none"}, {"next_tests", tests}});
    } catch (const orch::RequestError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  EXPECT_EQ(refusal(json::array({slender})), "(accepted)");
  EXPECT_EQ(refusal(slender), "next_tests: must be a list of a report's next tests");
  json lab = slender;
  lab["conditions"]["units"] = "lab";
  EXPECT_EQ(refusal(json::array({lab})),
            "next_tests[0].conditions.units: must be \"model\" (a twin is in model units)");
  json own = slender;
  own["id"] = "uct-peak";
  EXPECT_EQ(refusal(json::array({own})),
            "next_tests[0].id: must be a menu test's id (menu-...), as the report names it");
  EXPECT_EQ(refusal(json::array({slender, slender})),
            "next_tests[1].id: duplicate id 'menu-uct-hd3' (also next_tests[0])");
  json disc_height = slender;
  disc_height["test"] = "btt";
  EXPECT_EQ(refusal(json::array({disc_height})),
            "next_tests[0].conditions.height: a btt disc has no height (give thickness)");
  json slow = slender;
  slow["conditions"]["platen_velocity"] = -1;
  EXPECT_EQ(refusal(json::array({slow})).rfind("next_tests[0].conditions.platen_velocity: ", 0),
            0u);
}

// A finer-model twin keeps the continuum at a smaller radius (radius / f, K_r / f, strengths / f^2,
// as the budget's resolution variants do) and says where its numbers come from.
TEST(DiagnosisTwin, AFinerModelTwinRefinesItsSpecimens) {
  const TwinDesign d = make_twin_design(demo_twin_template(), formula_engine());
  std::vector<json> jobs;
  TwinRequest request{.effect = "none", .value = 0, .seed = 5, .noise = 0.02};
  request.resolution = 1.5;
  const Twin t = make_twin(d, request, formula_engine(&jobs));
  EXPECT_EQ(t.dataset.origin, Origin::finer_model);
  EXPECT_EQ(t.truth["resolution"], 1.5);
  ASSERT_FALSE(jobs.empty());
  for (const json& job : jobs) {
    EXPECT_DOUBLE_EQ(job["sample"]["radius"].get<double>(), 1.0 / 1.5);
    EXPECT_DOUBLE_EQ(job["material"]["kr"].get<double>(), 8000 / 1.5);
    EXPECT_DOUBLE_EQ(job["bond"]["fr0"].get<double>(), t.truth["fr0"].get<double>() / 2.25);
  }
  request.resolution = 0.5;
  EXPECT_THROW(make_twin(d, request, formula_engine()), orch::RequestError);
}

class DiagnosisTwinEngine : public ::testing::Test {
 protected:
  void SetUp() override {
    // rockcal-dem runs as an MPI singleton; Open MPI refuses root (CI) without these.
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);
    work_ = fs::temp_directory_path() / ("rockcal-dtwin-" + std::to_string(getpid()));
    fs::create_directories(work_);
  }
  void TearDown() override {
    if (service_) service_->stop();
    service_.reset();
    fs::remove_all(work_);
  }

  void start() {
    service_ = test::engine_service(work_ / "svc.db", ROCKCAL_DEM);
    service_->start();
  }

  json make(const json& request) {
    return test::run_to_summary(*service_, request, std::chrono::seconds(120));
  }

  std::int64_t runs() { return service_->store().durations().count; }

  fs::path work_;
  std::unique_ptr<orch::JobService> service_;
};

// The null case on the real engine, made by the "twin" kind: a dataset any diagnosis can read,
// with calibration and held-out observations, the same for the same seed, and made again from
// the job store without a run.
TEST_F(DiagnosisTwinEngine, NoneOnATinySampleIsAParseableDeterministicDataset) {
  start();
  const json request = {{"kind", "twin"}, {"effect", "none"}, {"seed", 5}};
  const json made = make(request);
  ASSERT_TRUE(made.is_object());
  EXPECT_GT(made["design"]["p_low"].get<double>(), 0);
  EXPECT_EQ(runs(), 1 + 8);
  // Its progress model planned those jobs before any ran (the design laid out without running).
  EXPECT_EQ(made["progress"], json::parse(R"({"unit": "jobs", "done": 9, "budget": 9,
    "parts": [{"name": "design", "budget": 1}, {"name": "observations", "budget": 8}],
    "left": 0, "fraction": 1.0, "eta_seconds": 0.0})"));
  EXPECT_EQ(made["truth"]["jobs"].size(), 8u);
  const Dataset parsed = parse_dataset_json(made["dataset"]);
  EXPECT_EQ(to_json(parse_dataset_csv(to_csv(parsed))), to_json(parsed));
  int calibration = 0, held_out = 0;
  for (const Observation& o : parsed.observations) {
    (o.role == Role::calibration ? calibration : held_out)++;
    EXPECT_GT(o.value, 0) << o.id;
  }
  EXPECT_EQ(calibration, 5);
  EXPECT_EQ(held_out, 5);  // uct-peak-strain shares the base UCT run: still 1 + 8 runs
  // The same seed again: the job store answers every run, and the noise is the seed's.
  const json again = make(request);
  EXPECT_EQ(runs(), 1 + 8);
  EXPECT_EQ(again["dataset"], made["dataset"]);
  EXPECT_EQ(again["truth"]["observations"], made["truth"]["observations"]);
  // A confined specimen carries more load; the squat UCT ran on a cylinder as high as it is wide.
  const auto value = [&](const std::string& id) { return find(parsed.observations, id).value; };
  EXPECT_GT(value("tri-high"), value("tri-low"));
  int squat = 0;
  for (const json& o : made["truth"]["observations"]) {
    if (o["id"] != "uct-squat") continue;
    const json& job = made["truth"]["jobs"].at(o["job"].get<std::size_t>());
    EXPECT_EQ(job["sample"]["height"], job["sample"]["diameter"]) << job.dump();
    ++squat;
  }
  EXPECT_EQ(squat, 1);
}

// `rockcal twin` end to end, with an effect on: the files it writes and what they hide.
TEST_F(DiagnosisTwinEngine, CommandWritesTheDatasetAndItsTruth) {
  const fs::path out = work_ / "twin.csv";
  const std::string command = std::string(ROCKCAL_BIN) + " twin --effect heterogeneity --value 3" +
                              " --seed 2 --out " + out.string() + " --engine " + ROCKCAL_DEM +
                              " > " + (work_ / "stdout").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << std::ifstream(work_ / "stdout").rdbuf();
  const Dataset d = read_dataset_file(out);
  EXPECT_EQ(d.observations.size(), 10u);
  // The engine's strain at the UCT's peak: a few per cent on a bonded packing, within max_strain.
  const Observation& strain = find(d.observations, "uct-peak-strain");
  EXPECT_GT(strain.value, 1e-3);
  EXPECT_LT(strain.value, demo_twin_template()["loading"]["max_strain"].get<double>());
  const json truth = json::parse(std::ifstream(work_ / "twin.truth.json"));
  EXPECT_EQ(truth["effect"], "heterogeneity");
  EXPECT_EQ(truth["value"], 3.0);
  EXPECT_EQ(truth["jobs"][0]["effects"]["heterogeneity"]["weibull_m"], 3.0);
  EXPECT_FALSE(fs::exists(work_ / "twin.csv.runs"));  // removed without --keep-runs
  std::ifstream text(out);
  std::stringstream all;
  all << text.rdbuf();
  EXPECT_EQ(all.str().find("heterogeneity"), std::string::npos);
}

}  // namespace
}  // namespace rockcal::diagnosis
