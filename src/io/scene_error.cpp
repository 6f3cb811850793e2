#include "ancf/io/scene_error.hpp"

#include <sstream>

namespace ancf {

namespace {
std::string compose(const std::string& file, int line, int column, const std::string& key,
                    const std::string& message) {
  std::ostringstream s;
  s << file;
  if (line > 0) s << ':' << line;
  if (line > 0 && column > 0) s << ':' << column;
  s << ": ";
  if (!key.empty()) s << key << ": ";
  s << message;
  return s.str();
}
}  // namespace

SceneError::SceneError(std::string file, int line, int column, std::string key, std::string message)
    : ModelError(compose(file, line, column, key, message)),
      file_(std::move(file)),
      key_(std::move(key)),
      message_(std::move(message)),
      line_(line),
      column_(column) {}

}  // namespace ancf
