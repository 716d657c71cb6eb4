#pragma once
// Values echoed in error messages, made safe to print on one line.
//
// An error message quotes the offending value so that users see what hsmap
// read ("expected a number, got '12abc'"). The value comes from a file that
// may be damaged: 100 KB of one cell, raw binary bytes, embedded newlines.
// Echoed whole it would flood the terminal, break the one-line rule of
// hsmap's errors and print garbage. escapeForMessage() therefore keeps a
// short prefix and writes every byte that is not printable UTF-8 as an
// escape: \n, \r, \t, \\ and \xNN (invalid UTF-8 bytes and control
// characters). Valid multi-byte UTF-8 characters (°, é, µ) are kept.

#include <cstddef>
#include <string>
#include <string_view>

namespace hsmap {

// At most `max_chars` characters of `text` (counting an escape as its
// printed length), escaped as above; when cut, "..." and the full size in
// bytes follow: "abcdef... (100000 bytes)".
std::string escapeForMessage(std::string_view text, std::size_t max_chars = 60);

// `value` with exactly `decimals` digits after the point ("0.125", "3.0"),
// as std::fixed prints it, for numbers in messages and summaries.
std::string fixedDecimals(double value, int decimals);

// escapeForMessage() between single quotes: 'abc'.
std::string quoteForMessage(std::string_view text, std::size_t max_chars = 60);

// Length in bytes of the valid UTF-8 sequence starting at text[0] (1 to 4),
// or 0 when text[0] does not start one (a stray continuation byte, an
// overlong form, a surrogate, a code point above U+10FFFF, a truncated
// sequence). Used by escapeForMessage() and by the text-file checks.
std::size_t utf8SequenceLength(std::string_view text);

}  // namespace hsmap
