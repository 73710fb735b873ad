#pragma once
// Reading LCM's wire format by hand, bounds-checked, for the checks that run on untrusted bytes
// before lcm-gen's decoders do: integers are big-endian, a string is an int32 length that
// counts the terminating NUL, then that many bytes.
#include <cstdint>
#include <exception>
#include <string>

namespace tongue::bus {

class WireReader {
 public:
  // The size bytes at data; see valid().
  WireReader(const void* data, int size);

  // False when size is negative, or data is null with size > 0: nothing can be read.
  bool valid() const { return valid_; }
  // Bytes not yet read.
  std::int64_t left() const { return valid_ ? size_ - pos_ : 0; }

  // The next big-endian integer. Throw std::logic_error when fewer bytes are left (the caller
  // checks left() first: the message's fixed part is checked once, not field by field).
  std::int64_t int64();
  std::int32_t int32();
  // Steps over count bytes; throws std::logic_error when fewer are left.
  void skip(std::int64_t count);

  // Steps over one string. Returns false, with reason naming field ("names[2]", "command"), when
  // its length is cut off, below 1, beyond the bytes left, or its last byte is not the NUL.
  bool string(const std::string& field, std::string& reason);

  // The checked steps of a message's layout; each returns false with reason naming field.
  // Steps over bytes bytes of fixed-size fields (cut off: truncated).
  bool fixed(const std::string& field, std::int64_t bytes, std::string& reason);
  // Reads an int32 count into n: rejected when cut off, negative, or when n elements of at least
  // min_bytes_each bytes each cannot fit in what is left (so nothing is sized by a hostile n).
  bool count(const std::string& field, std::int64_t min_bytes_each, std::int32_t& n,
             std::string& reason);
  // Steps over count strings named field[i].
  bool strings(const std::string& field, std::int32_t count, std::string& reason);
  // True when the check is at the end; otherwise false with reason counting trailing bytes.
  bool at_end(std::string& reason) const;

 private:
  std::uint64_t big_endian(int count);

  const unsigned char* bytes_;
  std::int64_t size_;
  std::int64_t pos_ = 0;
  bool valid_;
};

// Checks that data holds at least min_size bytes and starts with fingerprint; false with reason
// otherwise. in reads data; what prefixes reason ("lcmt_tongue_state: ").
bool start_message(WireReader& in, std::int64_t fingerprint, std::int64_t min_size,
                   const std::string& what, std::string& reason);

// lcm-gen's decode() of a message whose structure the caller has checked with a WireReader: the
// last step of every decoder here. False, with reason prefixed by what, when decode() still
// disagrees on the size or throws.
template <typename Message>
bool checked_decode(const void* data, int size, Message& out, const std::string& what,
                    std::string& reason) {
  try {
    if (out.decode(data, 0, size) != size) {
      reason = what + "lcm decode failed";
      return false;
    }
  } catch (const std::exception& e) {
    reason = what + "lcm decode failed: " + e.what();
    return false;
  }
  reason.clear();
  return true;
}

}  // namespace tongue::bus
