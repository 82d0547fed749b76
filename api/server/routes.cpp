#include "api/server/routes.hpp"

#include "api/server/http_util.hpp"
#include "api/server/metrics.hpp"
#include "api/server/views.hpp"
#include "engine/json_input.hpp"
#include "engine/spec.hpp"
#include "orchestrator/job_files.hpp"

namespace rockcal::api {

using nlohmann::json;
using Req = httplib::Request;
using Res = httplib::Response;

std::string path_regex(const std::string& path_template) {
  std::string out;
  bool in_param = false;
  for (char ch : path_template) {
    if (ch == '{') {
      in_param = true;
      out += "([^/]+)";
    } else if (ch == '}') {
      in_param = false;
    } else if (!in_param) {
      out += ch;
    }
  }
  return out;
}

namespace {

json parse_body(const Req& req) {
  try {
    return rockcal::parse_json_input(req.body);
  } catch (const rockcal::JsonInputError& e) {  // malformed, nested too deep, a key given twice
    throw HttpError(400, e.what(), e.field.empty() ? "(body)" : e.field);
  }
}

db::CampaignRow campaign_or_404(orch::JobService& svc, const Req& req) {
  auto id = parse_id(req.matches[1], "campaign id");
  auto c = svc.store().campaign(id);
  if (!c) throw HttpError(404, "no campaign " + std::to_string(id));
  return *c;
}

db::JobRow job_or_404(orch::JobService& svc, const Req& req) {
  auto id = parse_id(req.matches[1], "job id");
  auto j = svc.store().job(id);
  if (!j) throw HttpError(404, "no job " + std::to_string(id));
  return *j;
}

// A succeeded job's result, or the result a run without a peak kept for inspection (its job failed
// with a "no peak" error).
std::optional<db::ResultRow> result_of(orch::JobService& svc, const db::JobRow& j) {
  if (j.state != db::kSucceeded && j.state != db::kFailed) return std::nullopt;
  auto r = svc.store().result(j.hash);
  if (r && j.state == db::kFailed && !(r->no_peak && j.error == db::no_peak_error(*r->no_peak))) {
    return std::nullopt;
  }
  return r;
}

void create_campaign(ApiContext& ctx, const Req& req, Res& res) {
  json request = parse_body(req);
  auto id = ctx.service.create_campaign(request);
  auto c = ctx.service.store().campaign(id);
  json body = campaign_json(*c, orch::campaign_status(ctx.service.store(), *c, ctx.workers));
  res.set_header("Location", "/api/v1/campaigns/" + std::to_string(id));
  send_json(res, body, 201);
}

void list_campaigns(ApiContext& ctx, const Req& req, Res& res) {
  auto limit = query_int(req, "limit", 50, 1, 500);
  auto offset = query_int(req, "offset", 0, 0, INT64_MAX / 2);
  auto& store = ctx.service.store();
  json items = json::array();
  for (const auto& c : store.campaigns(limit, offset)) {
    items.push_back(campaign_json(c, orch::campaign_status(store, c, ctx.workers)));
  }
  send_json(res, {{"campaigns", items},
                  {"total", store.campaign_count()},
                  {"limit", limit},
                  {"offset", offset}});
}

void get_campaign(ApiContext& ctx, const Req& req, Res& res) {
  auto c = campaign_or_404(ctx.service, req);
  send_json(res, campaign_json(c, orch::campaign_status(ctx.service.store(), c, ctx.workers)));
}

void cancel_campaign(ApiContext& ctx, const Req& req, Res& res) {
  auto id = parse_id(req.matches[1], "campaign id");
  switch (ctx.service.cancel_campaign(id)) {
    case db::CancelOutcome::not_found:
      throw HttpError(404, "no campaign " + std::to_string(id));
    case db::CancelOutcome::already_finished:
      throw HttpError(409, "campaign " + std::to_string(id) + " has already finished");
    case db::CancelOutcome::cancelled:
      break;
  }
  auto c = ctx.service.store().campaign(id);
  send_json(res, campaign_json(*c, orch::campaign_status(ctx.service.store(), *c, ctx.workers)));
}

void campaign_results(ApiContext& ctx, const Req& req, Res& res) {
  auto c = campaign_or_404(ctx.service, req);
  std::string format = req.has_param("format") ? req.get_param_value("format") : "json";
  if (format != "json" && format != "csv") {
    throw HttpError(400, "format must be json or csv", "format");
  }
  auto rows = ctx.service.store().campaign_results(c.id, query_int(req, "limit", -1, 1, 10000),
                                                   query_int(req, "offset", 0, 0, INT64_MAX / 2));
  if (format == "csv") {
    res.set_content(results_csv(rows), "text/csv");
    return;
  }
  json items = json::array();
  for (const auto& row : rows) items.push_back(result_row_json(row));
  json points = json::array();
  for (const auto& p : orch::point_ensembles(rows)) points.push_back(point_json(p));
  send_json(res, {{"campaign_id", c.id}, {"results", items}, {"points", points}});
}

// A kind's HTML page of a finished campaign's summary (the diagnosis report), rendered from the
// stored summary alone.
void campaign_report(ApiContext& ctx, const Req& req, Res& res) {
  auto c = campaign_or_404(ctx.service, req);
  const orch::CampaignKind* kind = ctx.service.kinds().find(c.kind);
  if (!kind || !kind->report_html) {
    throw HttpError(404, "campaigns of kind " + c.kind + " have no HTML report");
  }
  if (c.driver_status.value_or("") != "done" || !c.summary) {
    throw HttpError(404, "campaign " + std::to_string(c.id) + " has no report yet (" +
                             c.driver_status.value_or("queued") + ")");
  }
  res.set_content(kind->report_html(json::parse(*c.summary)), "text/html; charset=utf-8");
}

// The files of the run that answered a job: its own, or for a job answered from the store the run
// that computed the stored result.
std::filesystem::path run_dir(ApiContext& ctx, const db::JobRow& j,
                              const std::optional<db::ResultRow>& r) {
  return orch::job_dir(ctx.service.jobs_dir(), r ? r->job_id : j.id);
}

void get_job(ApiContext& ctx, const Req& req, Res& res) {
  auto j = job_or_404(ctx.service, req);
  const auto r = result_of(ctx.service, j);
  json out = job_json(j, r, true);
  out["files"] =
      job_files_json(j, r, r ? orch::job_outputs(run_dir(ctx, j, r)) : orch::JobOutputs{});
  send_json(res, out);
}

// A file a finished run wrote, as an attachment named `name`.
void send_run_file(Res& res, const std::filesystem::path& file, const std::string& name,
                   const std::string& content_type) {
  auto text = orch::read_text(file);
  if (!text) throw HttpError(404, "the run wrote no " + name);
  res.set_header("Content-Disposition", "attachment; filename=\"" + name + "\"");
  res.set_content(*text, content_type);
}

void job_breaks(ApiContext& ctx, const Req& req, Res& res) {
  auto j = job_or_404(ctx.service, req);
  auto r = result_of(ctx.service, j);
  if (!r) throw HttpError(404, "job " + std::to_string(j.id) + " has no finished run");
  send_run_file(res, run_dir(ctx, j, r) / "breaks.csv", "breaks.csv", "text/csv");
}

// A VTK file by name: only a name the run's vtk/ directory lists is read, never a path from the
// request.
void job_vtk(ApiContext& ctx, const Req& req, Res& res) {
  auto j = job_or_404(ctx.service, req);
  auto r = result_of(ctx.service, j);
  if (!r) throw HttpError(404, "job " + std::to_string(j.id) + " has no finished run");
  const std::filesystem::path dir = run_dir(ctx, j, r);
  const std::string wanted = req.matches[2];
  for (const std::string& name : orch::job_outputs(dir).vtk) {
    if (name == wanted) return send_run_file(res, dir / "vtk" / name, name, "application/xml");
  }
  throw HttpError(404,
                  "job " + std::to_string(j.id) + " has no VTK file " + wanted +
                      " (VTK is written when the job's spec asks for \"output\": {\"vtk\": true})");
}

void job_log(ApiContext& ctx, const Req& req, Res& res) {
  auto j = job_or_404(ctx.service, req);
  // The path is built from the numeric id the store returned, never from the request text.
  auto file = orch::job_dir(ctx.service.jobs_dir(), j.id) / "log";
  if (!std::filesystem::exists(file)) {
    throw HttpError(
        404, j.cached ? "job was answered from the store and never ran" : "job has no log yet");
  }
  res.set_content(orch::tail_file(file, 1u << 30, 1u << 20), "text/plain");
}

void job_curve(ApiContext& ctx, const Req& req, Res& res) {
  auto j = job_or_404(ctx.service, req);
  auto r = result_of(ctx.service, j);
  if (!r || !r->curve) throw HttpError(404, "job " + std::to_string(j.id) + " has no load curve");
  res.set_content(*r->curve, "text/csv");
}

void query_results(ApiContext& ctx, const Req& req, Res& res) {
  db::ResultFilter f;
  if (req.has_param("test")) {
    f.test = req.get_param_value("test");
    if (!rockcal::test_kind_from_string(*f.test)) {
      throw HttpError(400, "test must be uct, btt, elastic or triaxial", "test");
    }
  }
  f.fr0_min = query_number(req, "fr0_min");
  f.fr0_max = query_number(req, "fr0_max");
  f.fs0_min = query_number(req, "fs0_min");
  f.fs0_max = query_number(req, "fs0_max");
  f.limit = query_int(req, "limit", 1000, 1, 10000);
  f.offset = query_int(req, "offset", 0, 0, INT64_MAX / 2);
  json items = json::array();
  for (const auto& r : ctx.service.store().results(f)) items.push_back(stored_result_json(r));
  send_json(res, {{"results", items}});
}

// 200 "ok", or 503 "storage_fault" while the database takes no write: a fault a write met is
// checked again with a probe write, so that the answer clears as soon as the fault does.
void health(ApiContext& ctx, const Req&, Res& res) {
  auto& store = ctx.service.store();
  auto fault = store.health().fault();
  if (fault) fault = store.probe_write();
  json body = {{"status", fault ? "storage_fault" : "ok"},
               {"engine_version", rockcal::engine_version()},
               {"workers", ctx.workers}};
  if (fault) {
    body["storage"] = {{"kind", fault->kind}, {"error", fault->message}, {"since", fault->since}};
  }
  send_json(res, body, fault ? 503 : 200);
}

}  // namespace

std::vector<Route> api_routes(ApiContext& ctx) {
  auto bind = [&ctx](void (*fn)(ApiContext&, const Req&, Res&)) {
    return [&ctx, fn](const Req& req, Res& res) { fn(ctx, req, res); };
  };
  return {
      {"GET", "/healthz", bind(health)},
      {"GET", "/metrics",
       [&ctx](const Req&, Res& res) {
         res.set_content(metrics_text(ctx.service, ctx.workers), "text/plain; version=0.0.4");
       }},
      {"POST", "/api/v1/campaigns", bind(create_campaign)},
      {"GET", "/api/v1/campaigns", bind(list_campaigns), {"limit", "offset"}},
      {"GET", "/api/v1/campaigns/{id}", bind(get_campaign)},
      {"DELETE", "/api/v1/campaigns/{id}", bind(cancel_campaign)},
      {"GET",
       "/api/v1/campaigns/{id}/results",
       bind(campaign_results),
       {"format", "limit", "offset"}},
      {"GET", "/api/v1/campaigns/{id}/report.html", bind(campaign_report)},
      {"GET", "/api/v1/jobs/{id}", bind(get_job)},
      {"GET", "/api/v1/jobs/{id}/log", bind(job_log)},
      {"GET", "/api/v1/jobs/{id}/curve", bind(job_curve)},
      {"GET", "/api/v1/jobs/{id}/breaks", bind(job_breaks)},
      {"GET", "/api/v1/jobs/{id}/vtk/{name}", bind(job_vtk)},
      {"GET",
       "/api/v1/results",
       bind(query_results),
       {"test", "fr0_min", "fr0_max", "fs0_min", "fs0_max", "limit", "offset"}},
  };
}

}  // namespace rockcal::api
