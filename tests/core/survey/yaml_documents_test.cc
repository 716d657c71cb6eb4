// parseYamlText: one document per file, found on the text (document markers)
// rather than by yaml-cpp's LoadAll, which never ends on some inputs.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <string>

#include "core/survey/strict_yaml_map.h"
#include "core/util/input_error.h"
#include "tests/support/expect_input_error.h"

namespace hsmap {
namespace {

using testing::expectInputError;

const std::string kSecondDocument =
    "a second YAML document starts here; expected the file to hold one document (remove what "
    "follows the first '---' / '...' document marker)";

TEST(YamlDocumentsTest, OneDocumentWithOrWithoutMarkersIsRead) {
  for (const char* text : {"a: 1\n", "---\na: 1\n", "%YAML 1.2\n---\na: 1\n...\n",
                           "# notes\n--- \na: 1\n...\n# trailing comment\n\n", "--- {a: 1}\n",
                           "a: |\n  ---- not a marker\n  text\n", "a: 1\n----\n"}) {
    SCOPED_TRACE(text);
    try {
      const YAML::Node node = parseYamlText(text, "f.yaml");
      ASSERT_TRUE(node.IsMap());
      EXPECT_EQ(node.begin()->first.Scalar(), "a");
    } catch (const InputError& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

TEST(YamlDocumentsTest, ContentAfterTheFirstDocumentIsAnErrorAtItsLine) {
  expectInputError([] { parseYamlText("a: 1\n...\nname: b\n", "f.yaml"); }, "f.yaml",
                   "line 3: " + kSecondDocument);
  expectInputError([] { parseYamlText("a: 1\n---\nb: 2\n", "f.yaml"); }, "f.yaml",
                   "line 2: " + kSecondDocument);
  expectInputError([] { parseYamlText("---\na: 1\n--- \n", "f.yaml"); }, "f.yaml",
                   "line 3: " + kSecondDocument);
  expectInputError([] { parseYamlText("a: 1\r...\rb\r", "f.yaml"); }, "f.yaml",
                   "line 3: " + kSecondDocument);
}

TEST(YamlDocumentsTest, InputsThatMadeLoadAllLoopEndPromptly) {
  // yaml-cpp 0.7's LoadAll() appends empty documents forever on these
  // (found by tests/fuzz/strict_yaml_fuzz); one document is read instead.
  // The parse runs on its own thread and must end within seconds, with a
  // value or a clean error naming the file.
  for (const char* text : {",", ",-", "\t\t, ca"}) {
    SCOPED_TRACE(text);
    auto parsed = std::async(std::launch::async, [text]() -> std::string {
      try {
        const YAML::Node node = parseYamlText(text, "f.yaml");
        return node.IsDefined() ? "value" : "undefined";
      } catch (const InputError& e) {
        return std::string("error: ") + e.what();
      }
    });
    ASSERT_EQ(parsed.wait_for(std::chrono::seconds(10)), std::future_status::ready) << "the parse did not end";
    const std::string outcome = parsed.get();
    if (outcome.rfind("error: ", 0) == 0) {
      EXPECT_EQ(outcome.rfind("error: f.yaml", 0), 0u) << outcome;
    } else {
      EXPECT_EQ(outcome, "value");
    }
  }
}

}  // namespace
}  // namespace hsmap
