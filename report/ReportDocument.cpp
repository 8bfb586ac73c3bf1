#include "report/ReportDocument.h"

#include <cctype>
#include <cstdio>

namespace candela::report_detail {

std::string fmt(const char* f, double a) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, a);
    return buf;
}

std::string typeset(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (size_t i = 0; i < s.size(); ++i) {
        const char c = s[i];
        const bool unitEnd = i + 1 >= s.size() || std::strchr(" )/,;.]", s[i + 1]) != nullptr;
        const bool afterM = i > 0 && s[i - 1] == 'm' &&
                            (i < 2 || !std::isalpha(static_cast<unsigned char>(s[i - 2])) ||
                             s[i - 2] == 'c' || s[i - 2] == 'k');
        if ((c == '2' || c == '3') && afterM && unitEnd) {
            out += c == '2' ? "\u00b2" : "\u00b3";
            continue;
        }
        if (s.compare(i, 2, ">=") == 0 || s.compare(i, 2, "<=") == 0) {
            out += c == '>' ? "\u2265" : "\u2264";
            ++i;
            continue;
        }
        if (s.compare(i, 5, "log10") == 0) {
            out += "log\u2081\u2080";
            i += 4;
            continue;
        }
        out += c;
    }
    return out;
}

std::string shortPath(const std::string& path) {
    size_t slash = path.find_last_of("/\\");
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string withoutPath(const std::string& note) {
    size_t colon = note.find(": ");
    if (colon == std::string::npos || note.substr(0, colon).find(' ') != std::string::npos)
        return note;
    return note.substr(colon + 2);
}

}  // namespace candela::report_detail
