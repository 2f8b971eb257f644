#pragma once
// What every fuzz target holds the code to: bad input ends in an error the service maps to a
// clear status (ServiceError with its code, SceneError / ImageError / std::invalid_argument as
// INVALID_ARGUMENT), never a crash, and never another exception, which the service would answer
// with INTERNAL for what is the client's mistake.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace strata::fuzz {

// Runs `f`; returns normally for success and for the expected errors; aborts (a finding) with the
// exception's type and message for any other exception.
void expect_clean(const char* target, const std::function<void()>& f);

// A path under which `bytes` can be read as a file (a memfd: no disk traffic per input).
class MemoryFile {
 public:
  MemoryFile();
  ~MemoryFile();
  const std::string& path() const { return path_; }
  void write(const uint8_t* data, size_t size);

 private:
  int fd_ = -1;
  std::string path_;
};

}  // namespace strata::fuzz
