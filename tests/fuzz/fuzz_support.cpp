#include "fuzz_support.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <typeinfo>

#include "image/image.h"
#include "scene/scene.h"
#include "service/errors.h"

namespace strata::fuzz {

void expect_clean(const char* target, const std::function<void()>& f) {
  try {
    f();
  } catch (const service::ServiceError& e) {
    if (e.code == grpc::StatusCode::OK || e.code == grpc::StatusCode::INTERNAL || e.code == grpc::StatusCode::UNKNOWN) {
      std::fprintf(stderr, "%s: ServiceError with status %d for bad input: %s\n", target, int(e.code), e.what());
      std::abort();
    }
  } catch (const scene::SceneError&) {
  } catch (const image::ImageError&) {
  } catch (const std::invalid_argument&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: unexpected %s (the service would answer INTERNAL): %s\n", target, typeid(e).name(), e.what());
    std::abort();
  }
}

MemoryFile::MemoryFile() {
  fd_ = memfd_create("strata-fuzz", 0);
  if (fd_ < 0) {
    std::perror("memfd_create");
    std::abort();
  }
  path_ = "/proc/self/fd/" + std::to_string(fd_);
}

MemoryFile::~MemoryFile() { close(fd_); }

void MemoryFile::write(const uint8_t* data, size_t size) {
  if (ftruncate(fd_, 0) != 0 || pwrite(fd_, data, size, 0) != ssize_t(size)) {
    std::perror("memfd write");
    std::abort();
  }
}

}  // namespace strata::fuzz
