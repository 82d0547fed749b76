// The dashboard's files (api/dashboard/), embedded into the binary at build time by
// api/embed_assets.cmake.
#pragma once

#include <span>
#include <string_view>

namespace rockcal::api {

struct EmbeddedFile {
  std::string_view path;  // relative to api/dashboard/, e.g. "plot/axes.js"
  std::string_view body;
};

std::span<const EmbeddedFile> dashboard_files();

}  // namespace rockcal::api
