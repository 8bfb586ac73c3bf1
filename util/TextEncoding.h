#pragma once
// Text files from other programs come in whatever encoding their authors' systems used. The
// photometry parsers read them as UTF-8 and keep what they show (names, lamp types, messages)
// valid UTF-8:
//  - a UTF-8 byte-order mark is dropped;
//  - UTF-16 (little- or big-endian, with a byte-order mark or recognised by its NUL bytes) is
//    transcoded to UTF-8;
//  - text that is not valid UTF-8 is read as Windows-1252, the Latin-1 superset that Windows
//    programs write, and transcoded to UTF-8.
// Transcoding goes through iconv (glibc); glibc's UTF-8 decoder accepts code points above
// U+10FFFF and 5-byte forms, so the UTF-8 check (RFC 3629's table) is done here.

#include <string>
#include <string_view>

namespace candela {

struct DecodedText {
    enum class Encoding { Utf8, Utf16LE, Utf16BE, Windows1252 };
    std::string utf8;  ///< The text, valid UTF-8, without a byte-order mark.
    Encoding encoding = Encoding::Utf8;
    bool byteOrderMark = false;  ///< The bytes started with a byte-order mark.
    /// 1-based line of the first byte that made the text Windows-1252 (first non-UTF-8 byte), or
    /// 1 for UTF-16; 0 for UTF-8.
    int firstLine = 0;
};

/// "UTF-8", "UTF-16LE", "UTF-16BE", "Windows-1252 (Latin-1)".
const char* encodingName(DecodedText::Encoding e);

/// Decodes bytes as described above. Throws InputError "PATH:LINE: ..." for UTF-16 that cannot be
/// decoded (an odd number of bytes, an unpaired surrogate).
DecodedText decodeText(std::string_view bytes, const std::string& pathForMessages);

/// Length of the longest prefix of `s` that is valid UTF-8 (RFC 3629: no overlong forms, no
/// surrogates, nothing above U+10FFFF).
size_t validUtf8Prefix(std::string_view s);
inline bool isValidUtf8(std::string_view s) {
    return validUtf8Prefix(s) == s.size();
}

/// `s` with every byte that is not part of valid UTF-8 read as Windows-1252 (Latin-1 where
/// Windows-1252 leaves a byte undefined), so any file name or field can go into a message.
std::string toValidUtf8(std::string_view s);

/// `s` as valid UTF-8 on one line (toValidUtf8, then control characters, line breaks and tabs
/// among them, as spaces): a file's text quoted in a one-line message.
std::string oneLine(std::string_view s);

/// `s` read as IBM code page 850 (DOS Latin-1), transcoded to UTF-8: what ZIP archives made on
/// Windows hold as member names when they do not flag them UTF-8.
std::string fromCodePage850(std::string_view s);

}  // namespace candela
