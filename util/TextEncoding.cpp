#include "util/TextEncoding.h"

#include <iconv.h>

#include <algorithm>
#include <cerrno>

#include "util/Error.h"

namespace candela {

namespace {

/// Bytes of the text looked at to recognise UTF-16 without a byte-order mark.
constexpr size_t kSniffBytes = 4096;

/// Owns an iconv conversion descriptor.
class Iconv {
  public:
    Iconv(const char* to, const char* from) : mCd(iconv_open(to, from)) {
        if (mCd == reinterpret_cast<iconv_t>(-1))
            throw RuntimeError(std::string("iconv cannot convert from ") + from + " to " + to);
    }
    ~Iconv() { iconv_close(mCd); }
    Iconv(const Iconv&) = delete;
    Iconv& operator=(const Iconv&) = delete;

    /// Appends the conversion of `in` to `out`; returns how many bytes of `in` converted (all of
    /// them unless a byte sequence is invalid or incomplete in the source encoding).
    size_t convert(std::string_view in, std::string& out) {
        iconv(mCd, nullptr, nullptr, nullptr, nullptr);  // initial shift state
        char* src = const_cast<char*>(in.data());
        size_t left = in.size();
        while (left > 0) {
            char buffer[4096];
            char* dst = buffer;
            size_t room = sizeof buffer;
            size_t r = iconv(mCd, &src, &left, &dst, &room);
            out.append(buffer, size_t(dst - buffer));
            if (r == size_t(-1) && errno != E2BIG) break;  // EILSEQ or EINVAL: stop at the bad byte
        }
        return in.size() - left;
    }

  private:
    iconv_t mCd;
};

/// 1-based line of byte `offset` (LF, CRLF or a lone CR end a line, as the parsers split).
int lineOf(std::string_view text, size_t offset) {
    int line = 1;
    for (size_t i = 0; i < offset && i < text.size(); ++i)
        if (text[i] == '\n' || (text[i] == '\r' && (i + 1 >= text.size() || text[i + 1] != '\n')))
            ++line;
    return line;
}

/// Windows-1252 to UTF-8; the five bytes Windows-1252 leaves undefined are read as Latin-1.
std::string fromWindows1252(std::string_view in) {
    Iconv cd("UTF-8", "WINDOWS-1252");
    std::string out;
    while (!in.empty()) {
        size_t done = cd.convert(in, out);
        if (done == in.size()) break;
        unsigned char c = static_cast<unsigned char>(in[done]);  // Latin-1: U+0080..U+00FF
        out += char(0xC0 | (c >> 6));
        out += char(0x80 | (c & 0x3F));
        in.remove_prefix(done + 1);
    }
    return out;
}

/// Recognises UTF-16 without a byte-order mark: plain-text files hold no NUL bytes, ASCII text
/// in UTF-16 has one in every other byte (odd offsets for little-endian).
bool sniffUtf16(std::string_view bytes, DecodedText::Encoding& encoding) {
    size_t n = std::min(bytes.size(), kSniffBytes) & ~size_t(1);
    size_t zeroEven = 0, zeroOdd = 0;
    for (size_t i = 0; i < n; ++i)
        if (bytes[i] == '\0') ++(i % 2 ? zeroOdd : zeroEven);
    size_t pairs = n / 2;
    if (pairs == 0) return false;
    // A quarter of the characters ASCII and (almost) no NUL on the other side.
    if (zeroOdd * 4 >= pairs && zeroEven * 8 <= zeroOdd) {
        encoding = DecodedText::Encoding::Utf16LE;
        return true;
    }
    if (zeroEven * 4 >= pairs && zeroOdd * 8 <= zeroEven) {
        encoding = DecodedText::Encoding::Utf16BE;
        return true;
    }
    return false;
}

}  // namespace

const char* encodingName(DecodedText::Encoding e) {
    switch (e) {
        case DecodedText::Encoding::Utf8:
            return "UTF-8";
        case DecodedText::Encoding::Utf16LE:
            return "UTF-16LE";
        case DecodedText::Encoding::Utf16BE:
            return "UTF-16BE";
        case DecodedText::Encoding::Windows1252:
            return "Windows-1252 (Latin-1)";
    }
    return "?";
}

size_t validUtf8Prefix(std::string_view s) {
    // RFC 3629, Sec. 4: the lead byte fixes the length and the range of the second byte.
    size_t i = 0;
    while (i < s.size()) {
        unsigned char c = static_cast<unsigned char>(s[i]);
        if (c < 0x80) {
            ++i;
            continue;
        }
        size_t length = 0;
        unsigned char lo = 0x80, hi = 0xBF;
        if (c >= 0xC2 && c <= 0xDF)
            length = 2;
        else if (c == 0xE0)
            length = 3, lo = 0xA0;  // no overlong forms
        else if (c >= 0xE1 && c <= 0xEC)
            length = 3;
        else if (c == 0xED)
            length = 3, hi = 0x9F;  // no surrogates
        else if (c >= 0xEE && c <= 0xEF)
            length = 3;
        else if (c == 0xF0)
            length = 4, lo = 0x90;
        else if (c >= 0xF1 && c <= 0xF3)
            length = 4;
        else if (c == 0xF4)
            length = 4, hi = 0x8F;  // nothing above U+10FFFF
        else
            return i;
        if (s.size() - i < length) return i;
        unsigned char second = static_cast<unsigned char>(s[i + 1]);
        if (second < lo || second > hi) return i;
        for (size_t k = 2; k < length; ++k)
            if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return i;
        i += length;
    }
    return s.size();
}

std::string toValidUtf8(std::string_view s) {
    std::string out;
    while (!s.empty()) {
        size_t ok = validUtf8Prefix(s);
        out.append(s.substr(0, ok));
        if (ok == s.size()) break;
        out += fromWindows1252(s.substr(ok, 1));
        s.remove_prefix(ok + 1);
    }
    return out;
}

std::string fromCodePage850(std::string_view s) {
    // Every byte is defined in code page 850, so iconv converts all of them.
    Iconv cd("UTF-8", "CP850");
    std::string out;
    cd.convert(s, out);
    return out;
}

DecodedText decodeText(std::string_view bytes, const std::string& path) {
    using E = DecodedText::Encoding;
    DecodedText d;
    auto startsWith = [&](std::string_view p) { return bytes.substr(0, p.size()) == p; };
    if (startsWith("\xEF\xBB\xBF")) {
        d.byteOrderMark = true;
        bytes.remove_prefix(3);
    } else if (startsWith("\xFF\xFE") || startsWith("\xFE\xFF")) {
        d.byteOrderMark = true;
        d.encoding = bytes[0] == '\xFF' ? E::Utf16LE : E::Utf16BE;
        bytes.remove_prefix(2);
    } else {
        sniffUtf16(bytes, d.encoding);
    }
    if (d.encoding == E::Utf16LE || d.encoding == E::Utf16BE) {
        d.firstLine = 1;
        Iconv cd("UTF-8", d.encoding == E::Utf16LE ? "UTF-16LE" : "UTF-16BE");
        size_t done = cd.convert(bytes, d.utf8);
        if (done != bytes.size()) {
            bool odd = bytes.size() % 2 != 0 && done + 1 == bytes.size();
            throw InputError(toValidUtf8(path) + ":" +
                             std::to_string(lineOf(d.utf8, d.utf8.size())) + ": expected " +
                             encodingName(d.encoding) + " text, found " +
                             (odd ? "an odd number of bytes"
                                  : "an invalid code unit sequence at byte " +
                                        std::to_string(done + (d.byteOrderMark ? 2 : 0))));
        }
        return d;
    }
    size_t ok = validUtf8Prefix(bytes);
    if (ok == bytes.size()) {
        d.utf8.assign(bytes);
        return d;
    }
    d.encoding = E::Windows1252;
    d.firstLine = lineOf(bytes, ok);
    d.utf8 = fromWindows1252(bytes);
    return d;
}

std::string oneLine(std::string_view s) {
    std::string out = toValidUtf8(s);
    for (char& c : out)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = ' ';
    return out;
}

}  // namespace candela
