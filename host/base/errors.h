// Errors carry the exit code the CLI returns for them, so every failure path ends in the
// documented code (docs/cli.md) without a switch at the top level.
#pragma once

#include <stdexcept>
#include <string>

namespace depthprec {

enum class ExitCode : int {
  ok = 0,
  internal = 1,  // a bug: an invariant of depthprec itself failed
  usage = 2,     // command line: unknown option, missing or malformed value
  input = 3,     // scene file, format or technique name, parameter out of range
  runtime = 4,   // OpenCL platform, device, program build or launch
  output = 5,    // an output file that cannot be written
  interrupted = 130,
};

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& what) : std::runtime_error(what), code_(code) {}
  ExitCode code() const { return code_; }

 private:
  ExitCode code_;
};

struct InputError : Error {
  explicit InputError(const std::string& what) : Error(ExitCode::input, what) {}
};
struct RuntimeError : Error {
  explicit RuntimeError(const std::string& what) : Error(ExitCode::runtime, what) {}
};
struct OutputError : Error {
  explicit OutputError(const std::string& what) : Error(ExitCode::output, what) {}
};

}  // namespace depthprec
