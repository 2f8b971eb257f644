#include "image/exr_memory_stream.h"

#include <cstring>
#include <string>

#include <OpenEXR/Iex.h>

namespace strata::image::detail {

MemoryOStream::MemoryOStream() : Imf::OStream("<memory>") {}

void MemoryOStream::write(const char c[], int n) {
  if (n <= 0) return;
  // OpenEXR seeks back to patch the line offset table, so a write may land inside the buffer.
  const uint64_t end = pos_ + static_cast<uint64_t>(n);
  if (end > bytes_.size()) bytes_.resize(end);
  std::memcpy(bytes_.data() + pos_, c, static_cast<size_t>(n));
  pos_ = end;
}

uint64_t MemoryOStream::tellp() { return pos_; }

void MemoryOStream::seekp(uint64_t pos) { pos_ = pos; }

MemoryIStream::MemoryIStream(std::span<const uint8_t> bytes, const char* name)
    : Imf::IStream(name), bytes_(bytes) {}

bool MemoryIStream::read(char c[], int n) {
  if (n < 0 || pos_ > bytes_.size() || static_cast<uint64_t>(n) > bytes_.size() - pos_) {
    // The same exception type OpenEXR's own file stream throws, so its error handling applies.
    throw IEX_NAMESPACE::InputExc(std::string("Unexpected end of file in ") + fileName() + ".");
  }
  std::memcpy(c, bytes_.data() + pos_, static_cast<size_t>(n));
  pos_ += static_cast<uint64_t>(n);
  return pos_ < bytes_.size();
}

uint64_t MemoryIStream::tellg() { return pos_; }

void MemoryIStream::seekg(uint64_t pos) { pos_ = pos; }

}  // namespace strata::image::detail
