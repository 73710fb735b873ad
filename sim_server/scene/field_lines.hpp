#pragma once
// The small text lists a scene may name beside its mesh (node lists, external points): fields
// separated by whitespace, ',' or ';', a '#' or '!' starting a comment to the end of the line,
// lines that may end in CRLF, bytes outside ASCII (Latin-1) in comments only. Read with a bound
// on the file's size, since a scene may point anywhere.
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace tongue::scene {

// "<path>, line <n>: <reason>", or "<path>: <reason>" for line 0 (the whole file).
[[noreturn]] void fail_in_file(const std::string& path, int line, const std::string& reason);

// Calls on_line(line number, its fields) for every line with a field, in order. Throws
// std::runtime_error (fail_in_file) for a missing or unreadable file, one larger than max_bytes,
// a non-ASCII byte outside a comment, or whatever on_line throws. what names the file's kind in
// the messages ("node list").
void for_each_field_line(
    const std::string& path, const std::string& what, std::uintmax_t max_bytes,
    const std::function<void(int, const std::vector<std::string_view>&)>& on_line);

}  // namespace tongue::scene
