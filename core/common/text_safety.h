#pragma once
// Text that came from a file we did not write ourselves (network metadata, file names) on its way into
// a network file, a terminal, a JSON document or a widget. "Safe" text is valid UTF-8 (RFC 3629: no
// overlong forms, no surrogates, nothing above U+10FFFF) without control characters: C0 (U+0000 to
// U+001F, tab and newline included: no network-file string uses them), DEL (U+007F) and C1 (U+0080 to
// U+009F). Why: a control character in metadata can drive the user's terminal ("\x1b]0;title\x07"
// retitles it), and invalid UTF-8 makes JSON writers throw.

#include <string>
#include <string_view>

namespace motionstyle {

// "" when `text` is safe; otherwise what is wrong with its first unsafe byte and the 0-based offset of
// that byte, e.g. "control character 0x1b at byte 4" or "invalid UTF-8 at byte 7".
std::string textSafetyProblem(std::string_view text);

// `text` with every unsafe part replaced by U+FFFD (the replacement character): each control character
// and each byte that does not begin a valid UTF-8 sequence becomes one U+FFFD. Safe text is returned
// unchanged, so safeText(safeText(s)) == safeText(s).
std::string safeText(std::string_view text);

// safeText() of each line, the newlines kept: for multi-line messages on their way to a terminal.
std::string safeLines(std::string_view text);

}  // namespace motionstyle
