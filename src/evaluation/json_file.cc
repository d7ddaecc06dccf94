#include "evaluation/json_file.h"

#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {

Json ReadJsonFile(const std::string& path) {
  const std::string text = ReadTextFile(path);
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& error) {
    // nlohmann's message names the byte offset and what it expected.
    ThrowError(path, ": invalid JSON: ", error.what());
  }
}

void WriteJsonFile(const std::string& path, const Json& value) {
  WriteFileAtomically(
      path, value.dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
}

}  // namespace colmap_gcn
