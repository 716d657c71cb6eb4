#pragma once
// expectInputError: the check that a reader rejects bad input with exactly
// the message users will see, shared by the tests of the survey readers.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "core/util/input_error.h"

namespace hsmap::testing {

// Expects `read` to throw InputError whose what() is exactly
// "<file>:<rest>" (the file as given, then where and detail), and whose
// file() is `file`.
template <typename Read>
void expectInputError(Read read, const std::filesystem::path& file, const std::string& rest) {
  try {
    read();
    ADD_FAILURE() << "no InputError; expected " << file.string() << ":" << rest;
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), file.string() + ":" + rest);
    EXPECT_EQ(e.file(), file);
  }
}

}  // namespace hsmap::testing
