// Replay driver: runs a fuzz target's LLVMFuzzerTestOneInput over files, so
// the seed corpora and the regression inputs of tests/fuzz/ run in the normal
// (gcc, no libFuzzer) build as CTest tests.
//
//   <target>_replay PATH...      each PATH a file or a folder (read recursively)
//
// Every input is copied into a heap buffer of exactly its size, as libFuzzer
// does, so a sanitizer build sees a read past its end. The inputs run in
// sorted path order and each is named on stderr before it runs, so a crash or
// an abort from the target points at its input.
//
// The limits of scripts/fuzz.sh apply here too, so that a regression input
// that hangs a parser and allocates without end (they exist: yaml-cpp's
// LoadAll on "," grows by ~150 MB/s) fails its test within seconds instead
// of taking the machine's memory: each input may run 10 s (libFuzzer's
// -timeout=10) and the process may hold 2048 MB of heap (-rss_limit_mb=2048;
// an allocation beyond it throws std::bad_alloc). The memory limit is left
// out under AddressSanitizer, whose shadow memory it would count.
//
// Exit status: 0 when every input ran; 2 for a missing or unreadable path (a
// misspelt corpus folder must not pass as an empty one); a finding ends the
// program the way it would end a libFuzzer run (abort, sanitizer report,
// uncaught exception), and a timeout with status 70 (libFuzzer's).

#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <system_error>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

#if defined(__SANITIZE_ADDRESS__)
#define HSMAP_REPLAY_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HSMAP_REPLAY_ASAN 1
#endif
#endif

namespace {

constexpr unsigned kTimeoutSeconds = 10;

// The message the SIGALRM handler writes (prepared before each input: a
// signal handler may only call async-signal-safe functions such as write).
char timeout_message[4096];
std::size_t timeout_message_size = 0;

void onTimeout(int) {
  [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, timeout_message, timeout_message_size);
  _exit(70);
}

void prepareTimeoutMessage(const std::filesystem::path& input) {
  const int size = std::snprintf(timeout_message, sizeof(timeout_message),
                                 "replay: timeout: %s ran for more than %u s\n", input.c_str(),
                                 kTimeoutSeconds);
  timeout_message_size = size < 0 ? 0 : std::min<std::size_t>(size, sizeof(timeout_message) - 1);
}

void limitMemory() {
#if !defined(HSMAP_REPLAY_ASAN)
  // RLIMIT_DATA counts the heap and private anonymous mappings, not the code
  // and read-only data of the shared libraries.
  constexpr rlim_t kMemoryLimitMb = 2048;
  const rlimit limit{kMemoryLimitMb << 20, kMemoryLimitMb << 20};
  if (setrlimit(RLIMIT_DATA, &limit) != 0) std::perror("replay: setrlimit(RLIMIT_DATA)");
#endif
}

bool readInput(const std::filesystem::path& file, std::vector<char>& bytes) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return !in.bad();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE_OR_FOLDER...\n", argv[0]);
    return 2;
  }
  std::vector<std::filesystem::path> inputs;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path path = argv[i];
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(path)) {
        if (entry.is_regular_file()) inputs.push_back(entry.path());
      }
    } else if (std::filesystem::is_regular_file(path, error)) {
      inputs.push_back(path);
    } else {
      std::fprintf(stderr, "replay: %s: no such file or folder\n", path.c_str());
      return 2;
    }
  }
  std::sort(inputs.begin(), inputs.end());
  limitMemory();
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = onTimeout;
  sigaction(SIGALRM, &action, nullptr);

  std::vector<char> bytes;
  for (const std::filesystem::path& input : inputs) {
    if (!readInput(input, bytes)) {
      std::fprintf(stderr, "replay: %s: cannot read\n", input.c_str());
      return 2;
    }
    std::fprintf(stderr, "replay: %s (%zu bytes)\n", input.c_str(), bytes.size());
    std::fflush(stderr);
    // Exactly sized (new[] of 0 is a valid, unique pointer for empty inputs).
    const std::unique_ptr<std::uint8_t[]> data(new std::uint8_t[bytes.size()]);
    std::copy(bytes.begin(), bytes.end(), data.get());
    prepareTimeoutMessage(input);
    alarm(kTimeoutSeconds);
    LLVMFuzzerTestOneInput(data.get(), bytes.size());
    alarm(0);
  }
  std::printf("replay: %zu inputs ran without a finding\n", inputs.size());
  return 0;
}
