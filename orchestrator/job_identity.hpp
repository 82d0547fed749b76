// A job's identity: the hash of its canonical spec (output block removed, but for the VTK snapshots
// it asks for) plus the engine version. Equal hashes mean a stored result answers the job.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "db/records.hpp"

namespace rockcal::orch {

// Lower-case hex SHA-256 of `data`.
std::string sha256_hex(const std::string& data);

// Hash of a canonical spec (as rockcal::to_json returns it) and the engine version.
std::string identity_hash(const nlohmann::json& canonical_spec, const std::string& engine_version);

// Validates a full job spec (with "test") through the engine and returns the job to store:
// canonical spec, identity hash, and the point (test, fr0, fs0) it computes.
// Throws RequestError naming the field, prefixed with `field_prefix` (e.g. "job.").
db::NewJob make_job(const nlohmann::json& job_spec, const std::string& field_prefix = "");

}  // namespace rockcal::orch
