#pragma once
// A flat binary record: what a run job and its result are sent as between processes (a pipe to a
// worker process, an MPI message to another rank) and kept as in the run cache (run_cache.hpp). Numbers travel as their bytes, so a double
// arrives bit for bit (printed text would round it); the order is the machine's own, which the
// processes of one job share (an MPI ensemble of mixed byte orders is not supported).
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace shard {

class ByteWriter {
 public:
  template <class T>
  void number(T value) {
    static_assert(std::is_arithmetic_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void text(std::string_view s) {
    number<std::uint64_t>(s.size());
    bytes_.append(s);
  }
  void numbers(const std::vector<double>& values) {
    number<std::uint64_t>(values.size());
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

// Reads what ByteWriter wrote, in the same order; throws naming `what` (the record's kind) when
// the record is shorter than its fields say.
class ByteReader {
 public:
  ByteReader(std::string_view bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}
  template <class T>
  T number() {
    static_assert(std::is_arithmetic_v<T>);
    T value{};
    std::memcpy(&value, take(sizeof value), sizeof value);
    return value;
  }
  std::string text() {
    const auto n = count(1);
    return std::string(take(n), n);
  }
  std::vector<double> numbers() {
    const auto n = count(sizeof(double));
    std::vector<double> values(n);
    if (n) std::memcpy(values.data(), take(n * sizeof(double)), n * sizeof(double));
    return values;
  }
  bool at_end() const { return at_ == bytes_.size(); }

 private:
  std::size_t count(std::size_t item_size) {
    const auto n = number<std::uint64_t>();
    if (n > (bytes_.size() - at_) / item_size) truncated();
    return static_cast<std::size_t>(n);
  }
  const char* take(std::size_t n) {
    if (n > bytes_.size() - at_) truncated();
    const char* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  [[noreturn]] void truncated() const {
    throw std::runtime_error(what_ + ": the record is cut short (written by another build of shard, or by a process "
                                     "that died while writing it)");
  }
  std::string_view bytes_;
  std::string what_;
  std::size_t at_ = 0;
};

}  // namespace shard
