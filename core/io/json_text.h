#pragma once
// JSON as papernet writes it (docs/reliability.md, "Found and fixed", finding 10).

#include <nlohmann/json.hpp>
#include <string>

namespace papernet {

/// `doc` as JSON text (`indent` as nlohmann's dump: -1 on one line), every string made valid
/// UTF-8. Text quoted from an input (an OBJ's material name, a bad token in an error message, an
/// option's name in a query string) is bytes, and JSON carries UTF-8 only: each invalid byte
/// becomes U+FFFD here, where nlohmann's own dump throws.
inline std::string json_text(const nlohmann::json& doc, int indent = -1) {
  return doc.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace papernet
