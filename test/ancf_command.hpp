// Running the `ancf` executable from a test: shared by the command-line tests. Needs the
// compile definitions ANCF_EXECUTABLE (path of the built `ancf`) and ANCF_SOURCE_DIR.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace ancf::testing {

inline const std::filesystem::path kSource = ANCF_SOURCE_DIR;

/// Exit status of `ancf ARGS` (output discarded); −1 if it did not exit normally.
inline int run_ancf(const std::string& args) {
  const std::string command = std::string(ANCF_EXECUTABLE) + " " + args + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace ancf::testing
