// The error every scene-file problem is reported as: where (file, line, column, key path) and
// what was expected. Derives from ModelError so callers that catch model errors see it too.
#pragma once

#include <string>

#include "ancf/core/error.hpp"

namespace ancf {

/// what() is "FILE:LINE:COLUMN: KEY: MESSAGE" (line/column omitted when unknown, key when the
/// problem is with the file as a whole), e.g.
///   "pendulum.toml:12:6: cable[0].section.EA: expected a number > 0, got -3".
/// Key paths count array entries from 0: cable[2] is the third [[cable]] table.
class SceneError : public ModelError {
 public:
  SceneError(std::string file, int line, int column, std::string key, std::string message);

  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] int line() const { return line_; }  ///< 1-based; 0: unknown
  [[nodiscard]] int column() const { return column_; }
  [[nodiscard]] const std::string& key() const { return key_; }
  [[nodiscard]] const std::string& message() const { return message_; }

 private:
  std::string file_, key_, message_;
  int line_ = 0, column_ = 0;
};

}  // namespace ancf
