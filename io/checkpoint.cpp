#include "io/checkpoint.hpp"

#include <array>
#include <cstring>
#include <stdexcept>

#include "io/files.hpp"

namespace twinflow::io {

namespace {

constexpr char kMagic[8] = {'T', 'W', 'F', 'C', 'K', 'P', 'T', '1'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeaderSize = 32;
constexpr std::size_t kTrailerSize = 4;

// The format is little-endian and stores doubles as raw host bytes: refuse any other host.
void require_little_endian_host() {
  const std::uint32_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  if (first != 1)
    throw std::runtime_error("checkpoint: this host is not little-endian; the format is");
}

// What the reader and the messages know of each record type: its name, its element size in bytes
// and whether it holds exactly one element.
struct RecordTypeFacts {
  RecordType type;
  const char* name;
  std::size_t element_size;
  bool scalar;
};
constexpr RecordTypeFacts kRecordTypes[] = {
    {RecordType::bytes, "bytes", 1, false},
    {RecordType::int64, "int64", 8, true},
    {RecordType::uint64, "uint64", 8, true},
    {RecordType::float64, "float64", 8, true},
    {RecordType::int64_array, "int64 array", 8, false},
    {RecordType::uint64_array, "uint64 array", 8, false},
    {RecordType::float64_array, "float64 array", 8, false},
    {RecordType::string, "string", 1, false},
};

// nullptr: not a RecordType (a damaged type tag).
const RecordTypeFacts* facts_of(RecordType type) {
  for (const RecordTypeFacts& f : kRecordTypes)
    if (f.type == type) return &f;
  return nullptr;
}

template <class T> void append_raw(std::string& out, T value) {
  char buf[sizeof(T)];
  std::memcpy(buf, &value, sizeof(T));
  out.append(buf, sizeof(T));
}

// Bounds-checked reading of the byte string; `what` names the field for the error message.
class Cursor {
public:
  Cursor(const std::string& bytes, std::size_t end, const std::string& source)
      : bytes_(bytes), end_(end), source_(source) {}
  template <class T> T take(const std::string& what) {
    T value;
    std::memcpy(&value, span(sizeof(T), what), sizeof(T));
    return value;
  }
  const char* span(std::uint64_t n, const std::string& what) {
    if (n > end_ - pos_)
      throw InputError(source_ + ": corrupt checkpoint: " + what + " runs past the records");
    const char* p = bytes_.data() + pos_;
    pos_ += static_cast<std::size_t>(n);
    return p;
  }
  std::size_t position() const { return pos_; }

private:
  const std::string& bytes_;
  std::size_t end_;
  std::size_t pos_ = 0;
  const std::string& source_;
};

std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}

} // namespace

std::uint32_t crc32(const void* data, std::size_t size, std::uint32_t crc) {
  static const std::array<std::uint32_t, 256> table = make_crc_table();
  const auto* p = static_cast<const unsigned char*>(data);
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) crc = table[(crc ^ p[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

const char* record_type_name(RecordType type) {
  const RecordTypeFacts* f = facts_of(type);
  return f ? f->name : "unknown type";
}

const Checkpoint::Record* Checkpoint::find(const std::string& name) const {
  for (const Record& r : records_)
    if (r.name == name) return &r;
  return nullptr;
}

void Checkpoint::add(const std::string& name, RecordType type, std::uint64_t count,
                     const void* data, std::size_t bytes) {
  if (name.empty()) throw std::invalid_argument("Checkpoint::put: empty record name");
  if (find(name)) throw std::invalid_argument("Checkpoint::put: record '" + name + "' put twice");
  Record r{name, type, count, std::string(bytes, '\0')};
  if (bytes > 0) std::memcpy(r.payload.data(), data, bytes);
  records_.push_back(std::move(r));
}

void Checkpoint::put_bytes(const std::string& name, const void* data, std::size_t size) {
  add(name, RecordType::bytes, size, data, size);
}

const Checkpoint::Record& Checkpoint::require(const std::string& name, RecordType type) const {
  const Record* r = find(name);
  if (!r) throw InputError(source_ + ": checkpoint has no record '" + name + "'");
  if (r->type != type)
    throw InputError(source_ + ": checkpoint record '" + name + "' is " +
                     record_type_name(r->type) + ", not " + record_type_name(type));
  return *r;
}

template <class E> std::vector<E> Checkpoint::elements(const Record& r) const {
  std::vector<E> out(r.payload.size() / sizeof(E));
  if (!out.empty()) std::memcpy(out.data(), r.payload.data(), out.size() * sizeof(E));
  return out;
}
template std::vector<double> Checkpoint::elements<double>(const Record&) const;
template std::vector<std::int64_t> Checkpoint::elements<std::int64_t>(const Record&) const;
template std::vector<std::uint64_t> Checkpoint::elements<std::uint64_t>(const Record&) const;

std::vector<std::uint8_t> Checkpoint::get_bytes(const std::string& name) const {
  const Record& r = require(name, RecordType::bytes);
  return std::vector<std::uint8_t>(r.payload.begin(), r.payload.end());
}

std::vector<std::string> Checkpoint::names() const {
  std::vector<std::string> out;
  for (const Record& r : records_) out.push_back(r.name);
  return out;
}

std::string Checkpoint::serialize() const {
  require_little_endian_host();
  std::string out(kMagic, sizeof kMagic);
  append_raw<std::uint32_t>(out, kVersion);
  append_raw<std::uint32_t>(out, 0);
  append_raw<std::uint64_t>(out, records_.size());
  const std::size_t size_offset = out.size();
  append_raw<std::uint64_t>(out, 0); // file size, filled in below
  for (const Record& r : records_) {
    append_raw<std::uint32_t>(out, static_cast<std::uint32_t>(r.name.size()));
    out += r.name;
    append_raw<std::uint8_t>(out, static_cast<std::uint8_t>(r.type));
    append_raw<std::uint64_t>(out, r.element_count);
    append_raw<std::uint64_t>(out, r.payload.size());
    out += r.payload;
  }
  const std::uint64_t file_size = out.size() + kTrailerSize;
  std::memcpy(&out[size_offset], &file_size, sizeof file_size);
  append_raw<std::uint32_t>(out, crc32(out.data(), out.size()));
  return out;
}

Checkpoint Checkpoint::deserialize(const std::string& bytes, const std::string& source) {
  require_little_endian_host();
  auto fail = [&](const std::string& what) -> InputError {
    return InputError(source + ": " + what);
  };
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw fail("not a twinflow checkpoint (no TWFCKPT1 magic)");
  if (bytes.size() < kHeaderSize + kTrailerSize)
    throw fail("truncated checkpoint (" + std::to_string(bytes.size()) +
               " bytes, header alone is " + std::to_string(kHeaderSize + kTrailerSize) + ")");
  Cursor header(bytes, kHeaderSize, source);
  header.span(sizeof kMagic, "magic");
  const auto version = header.take<std::uint32_t>("version");
  header.take<std::uint32_t>("reserved");
  const auto count = header.take<std::uint64_t>("record count");
  const auto file_size = header.take<std::uint64_t>("file size");
  if (version != kVersion)
    throw fail("checkpoint version " + std::to_string(version) + " is not supported (this build " +
               "reads " + std::to_string(kVersion) + ")");
  if (file_size != bytes.size())
    throw fail("truncated or corrupt checkpoint: " + std::to_string(bytes.size()) +
               " bytes, header says " + std::to_string(file_size));
  const std::size_t body = bytes.size() - kTrailerSize;
  std::uint32_t stored_crc;
  std::memcpy(&stored_crc, bytes.data() + body, sizeof stored_crc);
  if (crc32(bytes.data(), body) != stored_crc)
    throw fail("corrupt checkpoint: CRC-32 checksum mismatch");

  // The checksum matched: what follows can only fail for a file written by a buggy writer.
  Checkpoint c;
  c.source_ = source;
  Cursor in(bytes, body, source);
  in.span(kHeaderSize, "header");
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::string which = "record " + std::to_string(i);
    const auto name_size = in.take<std::uint32_t>(which + " name length");
    std::string name(in.span(name_size, which + " name"), name_size);
    const std::string what = which + " '" + name + "'";
    const auto type = static_cast<RecordType>(in.take<std::uint8_t>(what + " type"));
    const auto elements = in.take<std::uint64_t>(what + " element count");
    const auto payload_size = in.take<std::uint64_t>(what + " size");
    const char* payload = in.span(payload_size, what + " payload");
    const RecordTypeFacts* facts = facts_of(type);
    if (!facts) throw fail("corrupt checkpoint: " + what + " has an unknown type tag");
    const std::size_t esize = facts->element_size;
    // Division, not elements * esize: a damaged count must not overflow into a match.
    if (payload_size % esize != 0 || payload_size / esize != elements ||
        (facts->scalar && elements != 1))
      throw fail("corrupt checkpoint: " + what + " size does not match its type and count");
    if (c.find(name)) throw fail("corrupt checkpoint: " + what + " appears twice");
    c.records_.push_back(Record{std::move(name), type, elements,
                                std::string(payload, static_cast<std::size_t>(payload_size))});
  }
  if (in.position() != body) throw fail("corrupt checkpoint: bytes after the last record");
  return c;
}

void Checkpoint::write(const std::filesystem::path& path) const {
  write_file_atomically(path, serialize());
}

Checkpoint Checkpoint::read(const std::filesystem::path& path) {
  return deserialize(read_file(path), path.string());
}

} // namespace twinflow::io
