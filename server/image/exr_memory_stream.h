#pragma once
// Internal to strata_image: OpenEXR streams over memory, so that frames are encoded and decoded
// without temporary files (the service streams EXR bytes over gRPC).
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <OpenEXR/ImfIO.h>

namespace strata::image::detail {

class MemoryOStream final : public Imf::OStream {
 public:
  MemoryOStream();
  void write(const char c[], int n) override;
  uint64_t tellp() override;
  void seekp(uint64_t pos) override;
  std::vector<uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<uint8_t> bytes_;
  uint64_t pos_ = 0;
};

// Reads `bytes` without copying; they must outlive the stream. `name` is what errors report.
class MemoryIStream final : public Imf::IStream {
 public:
  MemoryIStream(std::span<const uint8_t> bytes, const char* name);
  bool read(char c[], int n) override;
  uint64_t tellg() override;
  void seekg(uint64_t pos) override;

 private:
  std::span<const uint8_t> bytes_;
  uint64_t pos_ = 0;
};

}  // namespace strata::image::detail
