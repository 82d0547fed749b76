// Reading and writing a dataset file, JSON or CSV by its extension.
#include <fstream>
#include <sstream>

#include "engine/json_input.hpp"
#include "orchestrator/diagnosis/dataset/dataset.hpp"

namespace rockcal::diagnosis {
namespace {

bool is_csv(const std::filesystem::path& file) {
  return file.extension() == ".csv";
}

}  // namespace

Dataset read_dataset_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::ostringstream text;
  text << in.rdbuf();
  try {
    if (is_csv(file)) return parse_dataset_csv(text.str());
    return parse_dataset_json(parse_json_input(text.str()));
  } catch (const JsonInputError& e) {
    throw std::runtime_error(file.string() + ": not JSON (" + e.what() + ")");
  } catch (const orch::RequestError& e) {
    // Keep the type and the field, so callers can still point at it; the message names the file.
    const std::string message = e.message;
    throw orch::RequestError(e.field, message + " [" + file.string() + "]");
  }
}

void write_dataset_file(const Dataset& d, const std::filesystem::path& file) {
  // Written whole to a temporary name first, so a reader never sees half a dataset.
  const std::filesystem::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp);
    if (is_csv(file)) {
      out << to_csv(d);
    } else {
      out << to_json(d).dump(2) << "\n";
    }
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::filesystem::rename(tmp, file);
}

}  // namespace rockcal::diagnosis
