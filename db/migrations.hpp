// Versioned schema migrations, applied in order at start-up.
#pragma once

#include <string>
#include <vector>

#include "db/sqlite.hpp"

namespace rockcal::db {

struct Migration {
  int version;
  std::string sql;
};

// Every migration the store knows, oldest first. New ones are appended, never edited.
const std::vector<Migration>& migrations();

// Applies the migrations newer than the database's schema_version, each in its own transaction.
// Returns the version the database is at afterwards.
int migrate(Connection& conn);

}  // namespace rockcal::db
