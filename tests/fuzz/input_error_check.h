#pragma once
// The property every fuzz target checks on the errors of a parser: bad input
// is reported as an hsmap::InputError whose message is one line (users see it
// as `error: <what()>`; a message with a line break in it breaks that rule
// and can forge extra lines in logs). A violation aborts, so libFuzzer (and
// the replay driver) report it like a crash, with the offending input.
//
// Any other exception is left to propagate: uncaught, it terminates the
// program, which libFuzzer also reports as a crash.

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/util/input_error.h"

namespace hsmap::fuzz {

inline void checkOneLine(const InputError& error) {
  const char* message = error.what();
  if (std::strpbrk(message, "\n\r") != nullptr) {
    std::fprintf(stderr, "fuzz: InputError message is not one line:\n---\n%s\n---\n", message);
    std::abort();
  }
}

}  // namespace hsmap::fuzz
