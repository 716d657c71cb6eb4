#pragma once
// Numbers in survey text files (CSV cells, YAML scalars), read strictly and
// written so that they read back bit-identically.
//
// Reading: the whole text must be one number (leading/trailing spaces and tabs
// are ignored, a leading '+' is accepted); anything else — an empty cell,
// "12abc", "1,5", "0x10" — is rejected. Non-finite values ("nan", "inf") are
// rejected too: no survey quantity is legitimately infinite or undefined, and a
// NaN that slips in silently poisons every estimate downstream.
//
// Writing: std::to_chars' shortest round-trip form, so a time stamp such as
// 1700000000.123456 keeps every digit (printf's %.9g would round it to
// 1.70000000e+09) and parse(format(x)) == x exactly.

#include <optional>
#include <string>
#include <string_view>

namespace hsmap {

// Parses a finite double. On failure returns nullopt and sets *message to
// "expected a number, got '<text>'" or "expected a finite number, got '<text>'".
std::optional<double> parseFiniteDouble(std::string_view text, std::string* message);

// Parses a base-10 integer that fits in long long. On failure sets *message to
// "expected an integer, got '<text>'".
std::optional<long long> parseInteger(std::string_view text, std::string* message);

// Shortest text that parses back to exactly `value` ("0.1", "1700000000.123456", "1e-07").
std::string formatDouble(double value);

// Removes leading and trailing spaces and tabs.
std::string_view trimBlanks(std::string_view text);

}  // namespace hsmap
