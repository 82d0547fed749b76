// The web dashboard: its pages at bookmarkable paths (/, /campaigns, /campaigns/{id}, /jobs/{id},
// /submit: all the same shell, whose script reads the path) and its embedded files under /ui/.
// The pages read and write only through the REST API, from the same origin.
#pragma once

#include <httplib.h>

#include <string>
#include <string_view>

namespace rockcal::api {

// The page paths the shell answers, as httplib patterns.
inline constexpr const char* kDashboardPages[] = {"/", "/campaigns", "/campaigns/[^/]+",
                                                  "/jobs/[^/]+", "/submit"};

void mount_dashboard(httplib::Server& server);

// "text/javascript; charset=utf-8" for "plot/axes.js": the file types the dashboard serves.
std::string content_type_of(std::string_view path);

}  // namespace rockcal::api
