// The dashboard's files (api/server/dashboard/), embedded into the binary at build time by
// api/server/embed_assets.cmake.
#pragma once

#include <span>
#include <string_view>

namespace rockcal::api {

struct EmbeddedFile {
  std::string_view path;  // relative to api/server/dashboard/, e.g. "plot/axes.js"
  std::string_view body;
};

std::span<const EmbeddedFile> dashboard_files();

}  // namespace rockcal::api
