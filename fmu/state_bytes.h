// The bytes of a serialized FMU state, field by field in native byte order (a state is read back
// by the same binary): the protocol (fmu_state.cpp) and the model adapter write and read their
// fields with these.
#pragma once

#include <cstddef>
#include <cstring>
#include <vector>

namespace chaindrive::fmu {

inline void putBytes(std::vector<char>& out, const void* p, std::size_t n) {
  const std::size_t at = out.size();
  out.resize(at + n);
  std::memcpy(out.data() + at, p, n);
}

template <class T>
void putField(std::vector<char>& out, const T& v) {
  putBytes(out, &v, sizeof v);
}

/// Reads fields one after the other; the caller has checked the size.
class ByteReader {
 public:
  explicit ByteReader(const char* data) : data_(data) {}
  void get(void* p, std::size_t n) {
    std::memcpy(p, data_ + pos_, n);
    pos_ += n;
  }
  template <class T>
  void field(T& v) {
    get(&v, sizeof v);
  }

 private:
  const char* data_;
  std::size_t pos_ = 0;
};

}  // namespace chaindrive::fmu
