#pragma once
// A restart file: named, typed binary records, stored bitwise (a restart must continue exactly).
//
// ---------------------------------------------------------------------------------------------
// FILE LAYOUT (version 1). This comment is the specification; checkpoint.cpp follows it.
// All integers little-endian; doubles are their raw IEEE-754 bytes (NaN payloads, -0.0 and
// denormals survive). Only little-endian hosts read or write it (others are refused).
//
//   offset  size  header
//   0       8     magic "TWFCKPT1"
//   8       4     u32 version = 1
//   12      4     u32 reserved = 0
//   16      8     u64 record count
//   24      8     u64 file size in bytes, trailer included (tells truncation from corruption)
//   32            records, in the order they were put:
//                   u32 name length, name bytes (UTF-8, no terminator),
//                   u8 type tag (RecordType), u64 element count, u64 payload bytes, payload
//   size-4  4     u32 CRC-32 (IEEE 802.3, as zlib's crc32) of every byte before it
// ---------------------------------------------------------------------------------------------

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

namespace twinflow::io {

enum class RecordType : std::uint8_t {
  bytes = 1,         // std::vector<std::uint8_t> (put_bytes / get_bytes)
  int64 = 2,         // std::int64_t
  uint64 = 3,        // std::uint64_t
  float64 = 4,       // double
  int64_array = 5,   // std::vector<std::int64_t>
  uint64_array = 6,  // std::vector<std::uint64_t>
  float64_array = 7, // std::vector<double>
  string = 8,        // std::string
};
const char* record_type_name(RecordType type);

class Checkpoint {
public:
  // Supported T: double, std::int64_t, std::uint64_t, std::vector of those three, std::string.
  // Other integers are widened (signed to int64, unsigned to uint64); read them back as those.
  // A name may be put once (a second put throws std::invalid_argument).
  template <class T> void put(const std::string& name, const T& value);
  void put(const std::string& name, const char* value) { put(name, std::string(value)); }
  void put_bytes(const std::string& name, const void* data, std::size_t size);

  // Throws InputError naming the file and the record if it is missing or of another type.
  template <class T> T get(const std::string& name) const;
  std::vector<std::uint8_t> get_bytes(const std::string& name) const;

  bool contains(const std::string& name) const { return find(name) != nullptr; }
  std::vector<std::string> names() const; // in the order they were put
  std::size_t size() const { return records_.size(); }

  // Writes to `path.tmp` and renames: an interrupted write leaves the previous checkpoint.
  void write(const std::filesystem::path& path) const;
  // Throws InputError naming the file: missing, truncated, bad magic/version, checksum mismatch.
  static Checkpoint read(const std::filesystem::path& path);

  // The file's bytes (what write() stores) and their parser; exposed for tests and tools.
  std::string serialize() const;
  static Checkpoint deserialize(const std::string& bytes, const std::string& source);

private:
  struct Record {
    std::string name;
    RecordType type;
    std::uint64_t element_count;
    std::string payload; // raw little-endian bytes
  };
  const Record* find(const std::string& name) const;
  void add(const std::string& name, RecordType type, std::uint64_t count, const void* data,
           std::size_t bytes);
  const Record& require(const std::string& name, RecordType type) const; // throws InputError
  template <class E> std::vector<E> elements(const Record& r) const;

  std::vector<Record> records_;
  std::string source_ = "<checkpoint in memory>"; // the file it was read from, for messages
};

// CRC-32 (IEEE 802.3, reflected, as zlib's crc32): crc32("123456789") == 0xCBF43926.
std::uint32_t crc32(const void* data, std::size_t size, std::uint32_t crc = 0);

// ---- template definitions ----------------------------------------------------------------------

template <class T> void Checkpoint::put(const std::string& name, const T& value) {
  if constexpr (std::is_same_v<T, double>) {
    add(name, RecordType::float64, 1, &value, sizeof value);
  } else if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool> && std::is_signed_v<T>) {
    const auto v = static_cast<std::int64_t>(value);
    add(name, RecordType::int64, 1, &v, sizeof v);
  } else if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    const auto v = static_cast<std::uint64_t>(value);
    add(name, RecordType::uint64, 1, &v, sizeof v);
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    add(name, RecordType::float64_array, value.size(), value.data(), value.size() * sizeof(double));
  } else if constexpr (std::is_same_v<T, std::vector<std::int64_t>>) {
    add(name, RecordType::int64_array, value.size(), value.data(),
        value.size() * sizeof(std::int64_t));
  } else if constexpr (std::is_same_v<T, std::vector<std::uint64_t>>) {
    add(name, RecordType::uint64_array, value.size(), value.data(),
        value.size() * sizeof(std::uint64_t));
  } else if constexpr (std::is_same_v<T, std::string>) {
    add(name, RecordType::string, value.size(), value.data(), value.size());
  } else {
    static_assert(!sizeof(T), "Checkpoint::put: unsupported type (see the list above)");
  }
}

template <class T> T Checkpoint::get(const std::string& name) const {
  if constexpr (std::is_same_v<T, double>) {
    return elements<double>(require(name, RecordType::float64)).at(0);
  } else if constexpr (std::is_same_v<T, std::int64_t>) {
    return elements<std::int64_t>(require(name, RecordType::int64)).at(0);
  } else if constexpr (std::is_same_v<T, std::uint64_t>) {
    return elements<std::uint64_t>(require(name, RecordType::uint64)).at(0);
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    return elements<double>(require(name, RecordType::float64_array));
  } else if constexpr (std::is_same_v<T, std::vector<std::int64_t>>) {
    return elements<std::int64_t>(require(name, RecordType::int64_array));
  } else if constexpr (std::is_same_v<T, std::vector<std::uint64_t>>) {
    return elements<std::uint64_t>(require(name, RecordType::uint64_array));
  } else if constexpr (std::is_same_v<T, std::string>) {
    return require(name, RecordType::string).payload;
  } else {
    static_assert(!sizeof(T), "Checkpoint::get: unsupported type (see put)");
  }
}

} // namespace twinflow::io
