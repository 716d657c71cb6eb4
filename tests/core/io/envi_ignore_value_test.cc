#include "core/io/envi_ignore_value.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/util/input_error.h"

namespace hsmap {
namespace {

EnviHeader headerWith(const std::string& key, const std::string& value) {
  EnviHeader header;
  header.other_fields.emplace_back("description of something else", "x");
  header.other_fields.emplace_back(key, value);
  return header;
}

TEST(EnviDataIgnoreValue, AbsentIsNone) {
  EXPECT_FALSE(enviDataIgnoreValue(EnviHeader{}, "a.hdr").has_value());
}

TEST(EnviDataIgnoreValue, KeyMatchesWhateverItsCaseAndBlanksAndBracesAreAllowed) {
  EXPECT_EQ(enviDataIgnoreValue(headerWith("data ignore value", "-9999"), "a.hdr"), -9999.0f);
  EXPECT_EQ(enviDataIgnoreValue(headerWith("Data  Ignore\tValue", " { 0.5 } "), "a.hdr"), 0.5f);
  EXPECT_EQ(enviDataIgnoreValue(headerWith("DATA IGNORE VALUE", "1e3"), "a.hdr"), 1000.0f);
}

TEST(EnviDataIgnoreValue, NanMarksNothingMore) {
  EXPECT_FALSE(enviDataIgnoreValue(headerWith("data ignore value", "nan"), "a.hdr").has_value());
}

TEST(EnviDataIgnoreValue, NanIsWrittenOnceInPlaceOfAnyEarlierValueAndReadsBack) {
  EnviHeader header = headerWith("Data  Ignore Value", "-9999");
  header.samples = header.lines = header.bands = 1;
  header.data_type = EnviDataType::float32;
  setDataIgnoreValueNaN(header);
  setDataIgnoreValueNaN(header);
  const std::string text = formatEnviHeader(header);
  EXPECT_NE(text.find("\ndata ignore value = NaN\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("9999"), std::string::npos) << text;
  const EnviHeader back = parseEnviHeader(text, "a.hdr");
  int ignore_keys = 0;
  for (const auto& [key, value] : back.other_fields) ignore_keys += key == "data ignore value";
  EXPECT_EQ(ignore_keys, 1);
  EXPECT_FALSE(enviDataIgnoreValue(back, "a.hdr").has_value());
  EXPECT_EQ(back.other_fields.front(), (std::pair<std::string, std::string>{"description of something else", "x"}));
}

TEST(EnviDataIgnoreValue, AnythingElseIsAnErrorNamingTheHeaderAndKey) {
  for (const std::string bad : {"none", "", "1.5x", "inf", "{}"}) {
    try {
      enviDataIgnoreValue(headerWith("data ignore value", bad), "dir/ortho.hdr");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& error) {
      EXPECT_EQ(std::string(error.what()),
                "dir/ortho.hdr:key data ignore value: expected a finite number or NaN, found '" + bad + "'");
    }
  }
}

}  // namespace
}  // namespace hsmap
