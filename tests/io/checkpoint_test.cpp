// Checkpoint: bitwise round trip, the documented byte layout, and errors for damaged files.
#include "io/checkpoint.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <limits>
#include <string>

#include "helpers.hpp"
#include "io/files.hpp"

namespace fs = std::filesystem;
using twinflow::io::Checkpoint;
using twinflow::io::InputError;
using twinflow::io::testing::input_error_of;
using twinflow::io::testing::ScratchDirTest;

namespace {

double from_bits(std::uint64_t bits) {
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

std::uint64_t bits_of(double d) {
  std::uint64_t b;
  std::memcpy(&b, &d, sizeof b);
  return b;
}

template <class T> T read_at(const std::string& bytes, std::size_t offset) {
  T v;
  std::memcpy(&v, bytes.data() + offset, sizeof v);
  return v;
}

class CheckpointTest : public ScratchDirTest {
protected:
  CheckpointTest() : ScratchDirTest("twinflow_checkpoint_test") {}
};

// Doubles whose bits an arithmetic or text round trip would change.
const std::vector<std::uint64_t> kTrickyDoubleBits = {
    0x7ff8000000000abcull, // quiet NaN with a payload
    0xfff8000000000001ull, // negative quiet NaN with a payload
    0x7ff0000000000001ull, // signalling NaN
    0x8000000000000000ull, // -0.0
    0x0000000000000001ull, // smallest denormal
    0x800fffffffffffffull, // largest negative denormal
    0x7ff0000000000000ull, // +inf
    0x3fb999999999999aull, // 0.1
    0x7fefffffffffffffull, // largest double
};

} // namespace

TEST(Crc32, MatchesTheStandardCheckValue) {
  EXPECT_EQ(twinflow::io::crc32("123456789", 9), 0xCBF43926u);
  EXPECT_EQ(twinflow::io::crc32("", 0), 0u);
}

TEST_F(CheckpointTest, RoundTripIsBitwise) {
  std::vector<double> x0;
  for (std::uint64_t b : kTrickyDoubleBits) x0.push_back(from_bits(b));
  const std::vector<std::int64_t> ids = {std::numeric_limits<std::int64_t>::min(), -1, 0,
                                         std::numeric_limits<std::int64_t>::max()};
  const std::vector<std::uint64_t> rng = {0, 0xdeadbeefcafef00dull,
                                          std::numeric_limits<std::uint64_t>::max()};
  const std::string text("integrator\0shardlow", 19); // embedded NUL kept
  const unsigned char raw[] = {0, 1, 0xff, 0x80};

  Checkpoint c;
  c.put("x0", x0);
  c.put("step", std::int64_t{-42});
  c.put("seed", std::uint64_t{0xffffffffffffffffull});
  c.put("dt", from_bits(0x7ff8000000000abcull));
  c.put("negative_zero", -0.0);
  c.put("small", 7); // int widens to int64
  c.put("ids", ids);
  c.put("rng_state", rng);
  c.put("note", text);
  c.put("empty", std::vector<double>{});
  c.put("empty_text", std::string());
  c.put_bytes("raw", raw, sizeof raw);
  const fs::path path = dir_ / "restart.ckpt";
  c.write(path);

  const Checkpoint r = Checkpoint::read(path);
  EXPECT_EQ(r.names(), c.names());
  const auto x0_read = r.get<std::vector<double>>("x0");
  ASSERT_EQ(x0_read.size(), x0.size());
  for (std::size_t i = 0; i < x0.size(); ++i)
    EXPECT_EQ(bits_of(x0_read[i]), kTrickyDoubleBits[i]) << "element " << i;
  EXPECT_EQ(r.get<std::int64_t>("step"), -42);
  EXPECT_EQ(r.get<std::uint64_t>("seed"), 0xffffffffffffffffull);
  EXPECT_EQ(bits_of(r.get<double>("dt")), 0x7ff8000000000abcull);
  EXPECT_EQ(bits_of(r.get<double>("negative_zero")), 0x8000000000000000ull);
  EXPECT_EQ(r.get<std::int64_t>("small"), 7);
  EXPECT_EQ(r.get<std::vector<std::int64_t>>("ids"), ids);
  EXPECT_EQ(r.get<std::vector<std::uint64_t>>("rng_state"), rng);
  EXPECT_EQ(r.get<std::string>("note"), text);
  EXPECT_TRUE(r.get<std::vector<double>>("empty").empty());
  EXPECT_EQ(r.get<std::string>("empty_text"), "");
  EXPECT_EQ(r.get_bytes("raw"), std::vector<std::uint8_t>(raw, raw + sizeof raw));
  // Writing what was read gives the same bytes: nothing is normalised on the way.
  EXPECT_EQ(r.serialize(), c.serialize());
  EXPECT_FALSE(fs::exists(dir_ / "restart.ckpt.tmp"));
}

// Pins the layout documented in checkpoint.hpp.
TEST(CheckpointLayout, MatchesTheHeaderComment) {
  Checkpoint c;
  c.put("step", std::int64_t{5});
  c.put("x", std::vector<double>{1.5, -2.0});
  const std::string b = c.serialize();

  EXPECT_EQ(b.substr(0, 8), "TWFCKPT1");
  EXPECT_EQ(read_at<std::uint32_t>(b, 8), 1u);  // version
  EXPECT_EQ(read_at<std::uint32_t>(b, 12), 0u); // reserved
  EXPECT_EQ(read_at<std::uint64_t>(b, 16), 2u); // record count
  EXPECT_EQ(read_at<std::uint64_t>(b, 24), b.size());
  std::size_t at = 32; // record 0: "step", int64 (tag 2), 1 element, 8 bytes
  EXPECT_EQ(read_at<std::uint32_t>(b, at), 4u);
  EXPECT_EQ(b.substr(at + 4, 4), "step");
  EXPECT_EQ(read_at<std::uint8_t>(b, at + 8), 2u);
  EXPECT_EQ(read_at<std::uint64_t>(b, at + 9), 1u);
  EXPECT_EQ(read_at<std::uint64_t>(b, at + 17), 8u);
  EXPECT_EQ(read_at<std::int64_t>(b, at + 25), 5);
  at += 33; // record 1: "x", float64 array (tag 7), 2 elements, 16 bytes
  EXPECT_EQ(read_at<std::uint32_t>(b, at), 1u);
  EXPECT_EQ(b.substr(at + 4, 1), "x");
  EXPECT_EQ(read_at<std::uint8_t>(b, at + 5), 7u);
  EXPECT_EQ(read_at<std::uint64_t>(b, at + 6), 2u);
  EXPECT_EQ(read_at<std::uint64_t>(b, at + 14), 16u);
  EXPECT_EQ(read_at<double>(b, at + 22), 1.5);
  EXPECT_EQ(read_at<double>(b, at + 30), -2.0);
  at += 38;
  ASSERT_EQ(at + 4, b.size()); // then only the CRC
  EXPECT_EQ(read_at<std::uint32_t>(b, at), twinflow::io::crc32(b.data(), at));
}

TEST_F(CheckpointTest, TruncatedFileIsAnErrorNamingTheFile) {
  Checkpoint c;
  c.put("x0", std::vector<double>{1, 2, 3});
  c.put("step", std::int64_t{10});
  const std::string full = c.serialize();
  const fs::path path = dir_ / "cut.ckpt";
  for (std::size_t n = 0; n < full.size(); ++n) {
    twinflow::io::write_file_atomically(path, full.substr(0, n));
    const std::string message = input_error_of([&] { Checkpoint::read(path); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    if (n >= 8) {
      EXPECT_NE(message.find("truncated"), std::string::npos) << n << ": " << message;
    }
  }
}

TEST_F(CheckpointTest, FlippedByteIsAChecksumError) {
  Checkpoint c;
  c.put("x0", std::vector<double>{1, 2, 3});
  c.put("name", std::string("ec-verlet"));
  const std::string full = c.serialize();
  const fs::path path = dir_ / "flipped.ckpt";
  for (std::size_t i = 0; i < full.size(); ++i) {
    std::string bad = full;
    bad[i] = static_cast<char>(bad[i] ^ 0x10);
    twinflow::io::write_file_atomically(path, bad);
    const std::string message = input_error_of([&] { Checkpoint::read(path); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    // Magic, version and size fields are checked (and named) before the checksum.
    const bool checked_before_crc = i < 12 || (i >= 24 && i < 32);
    if (!checked_before_crc) {
      EXPECT_NE(message.find("checksum"), std::string::npos) << "byte " << i << ": " << message;
    }
  }
}

TEST_F(CheckpointTest, MissingOrMistypedRecordIsAnErrorNamingIt) {
  Checkpoint c;
  c.put("step", std::int64_t{3});
  const fs::path path = dir_ / "restart.ckpt";
  c.write(path);
  const Checkpoint r = Checkpoint::read(path);
  std::string message = input_error_of([&] { r.get<std::vector<double>>("velocities"); });
  EXPECT_NE(message.find("'velocities'"), std::string::npos) << message;
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  message = input_error_of([&] { r.get<double>("step"); });
  EXPECT_NE(message.find("'step' is int64, not float64"), std::string::npos) << message;
  EXPECT_FALSE(r.contains("velocities"));
  EXPECT_TRUE(r.contains("step"));
}

TEST_F(CheckpointTest, OtherDamageIsReported) {
  EXPECT_NE(input_error_of([&] { Checkpoint::read(dir_ / "absent.ckpt"); }).find("absent.ckpt"),
            std::string::npos);
  twinflow::io::write_file_atomically(dir_ / "text.ckpt", "{\"not\": \"a checkpoint\"}");
  EXPECT_NE(input_error_of([&] {
              Checkpoint::read(dir_ / "text.ckpt");
            }).find("not a twinflow checkpoint"),
            std::string::npos);
  // A future version, with a valid checksum: refused by version, not by checksum.
  std::string future = Checkpoint().serialize();
  future[8] = 2;
  const std::uint32_t crc = twinflow::io::crc32(future.data(), future.size() - 4);
  std::memcpy(&future[future.size() - 4], &crc, 4);
  EXPECT_NE(input_error_of([&] {
              Checkpoint::deserialize(future, "future.ckpt");
            }).find("version 2 is not supported"),
            std::string::npos);
}

TEST_F(CheckpointTest, WriteReplacesAtomicallyAndNamesArePutOnce) {
  const fs::path path = dir_ / "restart.ckpt";
  Checkpoint first;
  first.put("step", std::int64_t{1});
  first.write(path);
  Checkpoint second;
  second.put("step", std::int64_t{2});
  second.write(path);
  EXPECT_EQ(Checkpoint::read(path).get<std::int64_t>("step"), 2);
  EXPECT_FALSE(fs::exists(dir_ / "restart.ckpt.tmp"));
  EXPECT_THROW(second.put("step", std::int64_t{3}), std::invalid_argument);
  EXPECT_THROW(second.put("", 1.0), std::invalid_argument);
}
