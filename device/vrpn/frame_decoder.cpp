#include "device/vrpn/frame_decoder.hpp"

#include <string>

namespace thx::vrpn {

void FrameDecoder::feed(std::span<const std::uint8_t> bytes) {
  if (error_) return;
  // Compact only here: frames handed out since the last feed() point into the buffer.
  if (pos_ > 0) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + std::ptrdiff_t(pos_));
    pos_ = 0;
  }
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

DecodeStep FrameDecoder::next() {
  if (error_) return *error_;
  const std::span<const std::uint8_t> avail = std::span(buffer_).subspan(pos_);
  if (avail.size() < kHeaderSize) return NeedMore{};
  Result<Header> header = decodeHeader(avail);
  if (!header) {
    error_ = header.error();
    return *error_;
  }
  const std::size_t size = frameSize(header->payload_length);
  if (avail.size() < size) return NeedMore{};
  pos_ += size;
  return Frame{*header, avail.subspan(kHeaderSize, header->payload_length)};
}

std::optional<Error> FrameDecoder::finish() const {
  if (error_) return error_;
  if (buffered() == 0) return std::nullopt;
  return Error{ErrorCode::kTruncated, "input ended inside a message (" + std::to_string(buffered()) + " bytes left)"};
}

}  // namespace thx::vrpn
