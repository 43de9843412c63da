// JSON text to a document, as nlohmann::json::parse reads it, with two holes closed that the
// scene loader cannot see afterwards: a key given twice in one object (the parser keeps the
// last value silently) and a number too large for a double (nlohmann names neither line nor key).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace game {

/// Where and why text is not a document the scene loader may read.
struct JsonError {
  std::string line_column;  ///< "LINE:COLUMN" (1-based) of the character at fault, or empty
  std::string message;      ///< the reason, led by the key path where one applies
};

/// Parses `text` into `root`; on failure returns false and fills `error`: a syntax error has a
/// line and column, a number too large for a double has both those and its key path
/// ("bodies[0].radius: the number 1e999 ..."), a key given twice in one object has the object's
/// key path ("bodies[0]: duplicate key \"radius\" ...").
bool ParseJsonChecked(std::string_view text, nlohmann::json& root, JsonError& error);

}  // namespace game
