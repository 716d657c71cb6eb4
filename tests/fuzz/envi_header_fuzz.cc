// libFuzzer target: the ENVI header parser (core/io/envi_header.h) on
// arbitrary bytes. The only acceptable outcomes are a parsed header or an
// hsmap::InputError with a one-line message; any other exception, a crash, a
// sanitizer report, a hang or a huge allocation is a finding (docs/FUZZING.md).

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/io/envi_header.h"
#include "core/util/input_error.h"
#include "tests/fuzz/input_error_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view raw(reinterpret_cast<const char*>(data), size);
  try {
    const hsmap::EnviHeader header = hsmap::parseEnviHeader(raw, "uhi/cube.hdr");
    // A header that parses describes a raster whose size fits in a file.
    static_cast<void>(header.dataBytes());
  } catch (const hsmap::InputError& error) {
    hsmap::fuzz::checkOneLine(error);
  }
  return 0;
}
