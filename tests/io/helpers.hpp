#pragma once
// What the io tests share: a fresh scratch directory per test, and the message of an expected
// InputError.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>
#include <utility>

#include "io/files.hpp"

namespace twinflow::io::testing {

// Runs `f`, expects an InputError, returns its message.
template <class F> std::string input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

// A test with its own empty directory dir_ (named after the prefix, the process and the test),
// removed afterwards.
class ScratchDirTest : public ::testing::Test {
protected:
  explicit ScratchDirTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           (prefix_ + "_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;

private:
  std::string prefix_;
};

} // namespace twinflow::io::testing
