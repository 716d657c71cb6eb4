#include "core/util/text_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/util/input_error.h"

namespace hsmap {

std::string readTextFile(const std::filesystem::path& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) {
    throw InputError(file, "", "cannot open the file: it is a directory");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    const int error = errno;
    throw InputError(file, "",
                     std::string("cannot open the file: ") +
                         (error != 0 ? std::strerror(error) : "unknown error"));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(file, "", "read error");
  return text.str();
}

}  // namespace hsmap
