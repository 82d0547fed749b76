// A job's files on the real engine: a job asked with VTK at a point already computed without it
// runs again (its identity includes the snapshots it asks for) and leaves the series, whose
// particles.pvd names each frame's time, load and displacement; a later identical VTK job is
// answered from the store with that run's files; breaks.csv and the curve are downloadable.
#include <gtest/gtest.h>

#include <regex>

#include "support.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

struct Finished {
  json campaign;
  json job;
};

Finished run_one(httplib::Client& c, const json& request) {
  auto r = c.Post("/api/v1/campaigns", request.dump(), "application/json");
  if (!r || r->status != 201) throw std::runtime_error(r ? r->body : "no response");
  const auto id = json::parse(r->body)["id"].get<std::int64_t>();
  Finished run{wait_campaign(c, id, 120s), nullptr};
  const json rows = get_json(c, "/api/v1/campaigns/" + std::to_string(id) + "/results");
  run.job = get_json(c, "/api/v1/jobs/" + rows["results"][0]["job_id"].dump());
  return run;
}

std::string body_of(httplib::Client& c, const std::string& path) {
  auto r = c.Get(path);
  if (!r) return "(no response)";
  EXPECT_EQ(r->status, 200) << path << ": " << r->body;
  return r->body;
}

TEST(JobFiles, VtkAskedAtACachedPointRunsAgainAndLeavesASeriesWithLoadAndTime) {
  TempDir dir;
  ServerProcess server(dir.path(),
                       {"--engine", engine_binary(), "--ranks-per-job", "1", "--workers", "2"});
  server.start();
  auto c = server.client();
  const json plain = sweep_request({"btt"}, {80}, {70});
  const Finished first = run_one(c, plain);
  ASSERT_EQ(first.campaign["state"], "succeeded") << first.campaign.dump(2);
  const std::string base = "/api/v1/jobs/" + first.job["id"].dump();
  EXPECT_EQ(first.job["files"]["curve_csv"], base + "/curve");
  EXPECT_EQ(first.job["files"]["breaks_csv"], base + "/breaks");
  EXPECT_EQ(first.job["files"]["vtk"], json::array());
  EXPECT_EQ(body_of(c, base + "/breaks").rfind("step,x,y,z,mode\n", 0), 0u);
  auto none = c.Get(base + "/vtk/particles.pvd");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 404);

  json with_vtk = plain;
  with_vtk["job"]["output"] = {{"vtk", true}, {"vtk_frames", 3}};
  const Finished second = run_one(c, with_vtk);
  ASSERT_EQ(second.campaign["state"], "succeeded") << second.campaign.dump(2);
  EXPECT_EQ(second.campaign["progress"]["cached"], 0);  // ran again: the stored run has no VTK
  const json& vtk = second.job["files"]["vtk"];
  const std::string base2 = "/api/v1/jobs/" + second.job["id"].dump();
  ASSERT_GE(vtk.size(), 4u) << vtk.dump();  // breaks.vtu, the series and at least two frames
  EXPECT_EQ(vtk[0], base2 + "/vtk/breaks.vtu");
  EXPECT_EQ(vtk[1], base2 + "/vtk/particles.pvd");
  const std::string pvd = body_of(c, base2 + "/vtk/particles.pvd");
  const std::regex dataset(
      R"re(<DataSet timestep="([^"]+)" part="0" file="(particles_\d{4}\.vtu)" step="\d+" load="([^"]+)" displacement="[^"]+"/>)re");
  std::size_t frames = 0;
  double last_time = -1.0;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), dataset);
       it != std::sregex_iterator(); ++it, ++frames) {
    const double time = std::stod((*it)[1]);
    EXPECT_GT(time, last_time) << pvd;
    last_time = time;
    EXPECT_EQ(vtk[2 + frames], base2 + "/vtk/" + (*it)[2].str());
    EXPECT_NE(body_of(c, base2 + "/vtk/" + (*it)[2].str()).find("Name=\"load\""),
              std::string::npos);
  }
  EXPECT_EQ(frames + 2, vtk.size()) << pvd;

  // The same VTK job again: answered from the store, with the files of the run that computed it.
  const Finished third = run_one(c, with_vtk);
  EXPECT_EQ(third.campaign["progress"]["cached"], 1);
  const std::string base3 = "/api/v1/jobs/" + third.job["id"].dump();
  ASSERT_EQ(third.job["files"]["vtk"].size(), vtk.size());
  EXPECT_EQ(third.job["files"]["vtk"][1], base3 + "/vtk/particles.pvd");
  EXPECT_EQ(body_of(c, base3 + "/vtk/particles.pvd"), pvd);
  auto outside = c.Get(base3 + "/vtk/..%2Fjob.json");
  ASSERT_TRUE(outside);
  EXPECT_EQ(outside->status, 404);
}

}  // namespace
}  // namespace rockcal::test
