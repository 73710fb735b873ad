#pragma once
// Text that came from outside (a name or string in a received message, a command-line value) as
// it may be printed in one line of a report: a forged name must not be able to start a line of
// its own (a "\n" followed by a fake "sim_server: shutdown"), move the terminal's cursor or fill
// the log with a megabyte of text.
#include <cstddef>
#include <string>
#include <string_view>

namespace tongue::common {

// Characters of text shown before it is cut (the muscle and command names are far shorter).
inline constexpr std::size_t kUntrustedTextShown = 64;

// text with '\\' as "\\\\", '\n', '\r', '\t' as "\\n", "\\r", "\\t", every other byte outside
// printable ASCII (0x20-0x7e) as "\\xNN"; cut after max_shown bytes of text, the cut marked
// "...(N bytes)" with N the full size.
std::string untrusted_text(std::string_view text, std::size_t max_shown = kUntrustedTextShown);

// untrusted_text in double quotes, for names in messages: "\"GGp_left\"".
std::string quoted_untrusted(std::string_view text, std::size_t max_shown = kUntrustedTextShown);

}  // namespace tongue::common
