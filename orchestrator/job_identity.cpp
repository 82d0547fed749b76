#include "orchestrator/job_identity.hpp"

#include <openssl/evp.h>

#include <stdexcept>

#include "engine/spec.hpp"
#include "orchestrator/request_error.hpp"

namespace rockcal::orch {

std::string sha256_hex(const std::string& data) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(data.data(), data.size(), digest, &length, EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("sha256 failed");
  }
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < length; ++i) {
    out += hex[digest[i] >> 4];
    out += hex[digest[i] & 0xf];
  }
  return out;
}

std::string identity_hash(const nlohmann::json& canonical_spec, const std::string& engine_version) {
  nlohmann::json identity = canonical_spec;
  // The output block changes no result, but a run asked for VTK snapshots must leave them: such a
  // job is answered only by a run that wrote the same snapshots. Without VTK the block is left out
  // (the identities of such jobs are what they always were).
  const nlohmann::json output = identity.value("output", nlohmann::json::object());
  identity.erase("output");
  if (output.value("vtk", false))
    identity["output"] = {{"vtk", true}, {"vtk_frames", output.value("vtk_frames", 0)}};
  // nlohmann::json objects keep keys sorted, so dump() is canonical for equal specs.
  return sha256_hex(identity.dump() + "\n" + engine_version);
}

db::NewJob make_job(const nlohmann::json& job_spec, const std::string& field_prefix) {
  nlohmann::json canonical;
  try {
    canonical = rockcal::to_json(rockcal::parse_job(job_spec));
  } catch (const rockcal::SpecError& e) {
    throw RequestError(field_prefix + e.field, e.message);
  }
  db::NewJob job;
  job.test = canonical.at("test").get<std::string>();
  job.fr0 = canonical.at("bond").at("fr0").get<double>();
  job.fs0 = canonical.at("bond").at("fs0").get<double>();
  job.spec = canonical.dump();
  job.hash = identity_hash(canonical, rockcal::engine_version());
  return job;
}

}  // namespace rockcal::orch
