// Real-world leniency with honesty (issue 18, part 5): every leniency of the IES and EULUMDAT
// parsers loads the same table as the strict file it departs from, with one warning naming the
// file and the line, and strict mode refuses it with a one-line error naming the file, the line
// and the leniency. Defective values are errors; every message is valid UTF-8.

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "TestUtil.h"
#include "formats/Photometry.h"
#include "util/TextEncoding.h"

namespace candela {
namespace {

constexpr PhotometryOptions kStrict{.strict = true};
constexpr PhotometryOptions kLenient{.strict = false};

// ---------------------------------------------------------------------------------------------
// Files that follow their formats exactly (no warnings), built line by line so a test can change
// one line and know its number.

/// A EULUMDAT file, Isym 0, C planes 0, 90, 180, 270, gamma 0, 45, 90; one lamp set of 2000 lm.
/// Line numbers: 1-26 header, 27-32 the lamp set (28 type, 30 colour temperature, 31 CRI,
/// 32 wattage), 33-42 the direct ratios, 43-46 C angles, 47-49 gamma angles, 50-61 intensities.
std::vector<std::string> ldtLines() {
    std::vector<std::string> l = {"Test company",
                                  "1",
                                  "0",
                                  "4",
                                  "90",
                                  "3",
                                  "45",
                                  "REPORT",
                                  "Test luminaire",
                                  "NUM",
                                  "file.ldt",
                                  "date",
                                  "600",
                                  "0",
                                  "50",
                                  "500",
                                  "0",
                                  "0",
                                  "0",
                                  "0",
                                  "0",
                                  "100",
                                  "80",
                                  "1",
                                  "0",
                                  "1",
                                  "1",
                                  "LED",
                                  "2000",
                                  "3000K",
                                  "80",
                                  "20"};
    for (int k = 0; k < 10; ++k) l.push_back("0.5");
    for (const char* c : {"0", "90", "180", "270"}) l.push_back(c);
    for (const char* g : {"0", "45", "90"}) l.push_back(g);
    // Intensities in cd/klm: plane p (0..3), gamma index v: 100 + 10 p - 20 v.
    for (int p = 0; p < 4; ++p)
        for (int v = 0; v < 3; ++v) l.push_back(std::to_string(100 + 10 * p - 20 * v));
    return l;
}

/// An LM-63-2002 file, quadrant symmetry: vertical angles 0, 45, 90 and horizontal 0, 90.
/// Lines: 1 header, 2 [MANUFAC], 3 [LUMINAIRE], 4 TILT, 5 lamp line, 6 ballast line, 7 vertical,
/// 8 horizontal, 9-10 candela.
std::vector<std::string> iesLines() {
    return {"IESNA:LM-63-2002",
            "[MANUFAC] Maker",
            "[LUMINAIRE] Test luminaire",
            "TILT=NONE",
            "1 1000 1 3 2 1 2 0.1 0.2 0",
            "1 1 10",
            "0 45 90",
            "0 90",
            "300 200 100",
            "310 210 110"};
}

std::string join(const std::vector<std::string>& lines, const std::string& end = "\n") {
    std::string s;
    for (const std::string& l : lines) s += l + end;
    return s;
}

PhotometricData parse(const std::string& text, const std::string& path,
                      const PhotometryOptions& o) {
    return path.size() > 4 && path.substr(path.size() - 4) == ".ldt" ? parseEulumdat(text, path, o)
                                                                     : parseIes(text, path, o);
}

/// UTF-16 bytes of ASCII or Latin-1 text (each byte one code unit), with or without a BOM.
std::string utf16(const std::string& latin1, bool littleEndian, bool bom) {
    std::string out;
    if (bom) out += littleEndian ? "\xFF\xFE" : "\xFE\xFF";
    for (char c : latin1) {
        char hi = '\0';
        out += littleEndian ? std::string{c, hi} : std::string{hi, c};
    }
    return out;
}

struct Leniency {
    std::string name;
    std::string path;     ///< "t.ldt" or "t.ies": picks the parser.
    std::string text;     ///< The lenient file.
    std::string warning;  ///< The one warning it must give, in full ("t.ldt:30: ...; ...").
    std::string
        refusal;  ///< What strict mode's message must contain besides "(refused by --strict)".
    /// Extra checks of the loaded data (the table is compared with the strict file's anyway).
    std::function<void(const PhotometricData&)> check = [](const PhotometricData&) {};
};

/// The strict EULUMDAT file with `edit` applied to its lines.
std::string ldtWith(const std::function<void(std::vector<std::string>&)>& edit) {
    std::vector<std::string> l = ldtLines();
    edit(l);
    return join(l);
}

/// The strict IES file with `edit` applied to its lines.
std::string iesWith(const std::function<void(std::vector<std::string>&)>& edit) {
    std::vector<std::string> l = iesLines();
    edit(l);
    return join(l);
}

/// A check that the loaded data keep the keyword `key` with the value `expected`.
std::function<void(const PhotometricData&)> keywordIs(const std::string& key,
                                                      const std::string& expected) {
    return [key, expected](const PhotometricData& d) {
        auto it = std::find_if(d.keywords.begin(), d.keywords.end(),
                               [&](const auto& kv) { return kv.first == key; });
        ASSERT_NE(it, d.keywords.end()) << key;
        EXPECT_EQ(it->second, expected);
    };
}

/// EULUMDAT: empty optional fields.
void ldtEmptyFields(std::vector<Leniency>& c) {
    c.push_back(
        {"ldt empty direct ratios", "t.ldt", ldtWith([](auto& l) {
             for (int k = 32; k < 42; ++k) l[size_t(k)] = "";
         }),
         "t.ldt:33-42: the ten direct ratios are empty; left unknown (Candela does not use them)",
         "t.ldt:33-42: the ten direct ratios are empty",
         keywordIs("direct ratios", "? ? ? ? ? ? ? ? ? ?")});
    c.push_back({"ldt some empty direct ratios", "t.ldt",
                 ldtWith([](auto& l) { l[34] = l[36] = "  "; }),
                 "t.ldt:35-37: 2 of the ten direct ratios are empty; left unknown (Candela does "
                 "not use them)",
                 "t.ldt:35-37: 2 of the ten direct ratios are empty",
                 keywordIs("direct ratios", "0.5 0.5 ? 0.5 ? 0.5 0.5 0.5 0.5 0.5")});
    c.push_back({"ldt empty colour temperature", "t.ldt", ldtWith([](auto& l) { l[29] = ""; }),
                 "t.ldt:30: empty colour temperature of lamp set 1; left unknown",
                 "t.ldt:30: empty colour temperature of lamp set 1"});
    c.push_back({"ldt empty CRI", "t.ldt", ldtWith([](auto& l) { l[30] = " "; }),
                 "t.ldt:31: empty colour rendering index of lamp set 1; left unknown",
                 "t.ldt:31: empty colour rendering index of lamp set 1"});
    c.push_back({"ldt empty lamp type", "t.ldt", ldtWith([](auto& l) { l[27] = ""; }),
                 "t.ldt:28: empty lamp type of lamp set 1; left unknown",
                 "t.ldt:28: empty lamp type of lamp set 1"});
    c.push_back({"ldt empty wattage", "t.ldt", ldtWith([](auto& l) { l[31] = ""; }),
                 "t.ldt:32: empty wattage of lamp set 1; taken as 0 W",
                 "t.ldt:32: empty wattage of lamp set 1",
                 [](const PhotometricData& d) { EXPECT_EQ(d.inputWatts, 0.0); }});
    c.push_back({"ldt empty DFF", "t.ldt", ldtWith([](auto& l) { l[21] = ""; }),
                 "t.ldt:22: empty downward flux fraction DFF (%); left unknown",
                 "t.ldt:22: empty downward flux fraction DFF (%)"});
    c.push_back({"ldt empty conversion factor", "t.ldt", ldtWith([](auto& l) { l[23] = ""; }),
                 "t.ldt:24: empty conversion factor for luminous intensities; taken as 1",
                 "t.ldt:24: empty conversion factor"});
    c.push_back({"ldt conversion factor 0", "t.ldt", ldtWith([](auto& l) { l[23] = "0"; }),
                 "t.ldt:24: conversion factor 0; taken as 1", "t.ldt:24: conversion factor 0"});
    c.push_back({"ldt empty tilt", "t.ldt", ldtWith([](auto& l) { l[24] = ""; }),
                 "t.ldt:25: empty tilt of the luminaire during measurement (degrees); taken as 0",
                 "t.ldt:25: empty tilt of the luminaire"});
}

/// EULUMDAT: a repeated last C plane, as C360 (a copy of C0) and as the last angle twice.
void ldtRepeatedPlanes(std::vector<Leniency>& c) {
    c.push_back({"ldt C360 repeating C0", "t.ldt", ldtWith([](auto& l) {
                     l[3] = "5";
                     l.insert(l.begin() + 46, "360");
                     l.insert(l.end(), {"100", "80", "60"});
                 }),
                 "t.ldt:47: C360 repeats the C0 plane (counted in Mc = 5); dropped",
                 "t.ldt:47: C360 repeats the C0 plane"});
    c.push_back({"ldt C360 differing from C0", "t.ldt", ldtWith([](auto& l) {
                     l[3] = "5";
                     l.insert(l.begin() + 46, "360");
                     l.insert(l.end(), {"100", "80", "61.5"});
                 }),
                 "t.ldt:47: C360 repeats the C0 plane (counted in Mc = 5); dropped (its "
                 "intensities differ from "
                 "C0's by up to 1.5 cd/klm)",
                 "t.ldt:47: C360 repeats the C0 plane"});
    c.push_back({"ldt C360 without its intensities", "t.ldt", ldtWith([](auto& l) {
                     l[3] = "5";
                     l.insert(l.begin() + 46, "360");
                 }),
                 "t.ldt:47: C360 repeats the C0 plane (counted in Mc = 5); dropped",
                 "t.ldt:47: C360 repeats the C0 plane"});
    c.push_back({"ldt last angle twice", "t.ldt", ldtWith([](auto& l) {
                     l[3] = "5";
                     l.insert(l.begin() + 46, "270");
                     l.insert(l.end(), {"130", "110", "90"});
                 }),
                 "t.ldt:47: C270 repeats the plane before it (counted in Mc = 5); dropped",
                 "t.ldt:47: C270 repeats the plane before it"});
}

/// EULUMDAT: numbers and values the format does not allow.
void ldtValues(std::vector<Leniency>& c) {
    c.push_back({"ldt decimal comma", "t.ldt", ldtWith([](auto& l) { l[22] = "80,0"; }),
                 "t.ldt:23: a decimal comma (not in EULUMDAT); read as a decimal point",
                 "t.ldt:23: a decimal comma"});
    c.push_back({"ldt LORL 0", "t.ldt", ldtWith([](auto& l) { l[22] = "0"; }),
                 "t.ldt:23: light output ratio LORL 0 %; no declared luminaire flux (the "
                 "intensities are still "
                 "cd/klm of the lamp flux)",
                 "t.ldt:23: light output ratio LORL 0 %", [](const PhotometricData& d) {
                     EXPECT_EQ(d.declaredFlux(), 0.0);
                     EXPECT_EQ(d.lampFlux, 2000.0);
                 }});
    c.push_back({"ldt values after the intensities", "t.ldt",
                 ldtWith([](auto& l) { l.push_back("7 8"); }),
                 "t.ldt:62: 2 values after the intensities (from '7'); ignored",
                 "t.ldt:62: 2 values after the intensities"});
}

/// Text: trailing blank lines, mixed line endings, encodings (both formats).
void textLeniencies(std::vector<Leniency>& c) {
    for (const std::string path : {"t.ldt", "t.ies"}) {
        bool isLdt = path == "t.ldt";
        std::vector<std::string> lines = isLdt ? ldtLines() : iesLines();
        int n = int(lines.size());
        c.push_back({path + " trailing blank lines", path, join(lines) + "\n \n\t\n",
                     path + ":" + std::to_string(n + 1) + "-" + std::to_string(n + 3) +
                         ": 3 trailing blank lines; ignored",
                     path + ":" + std::to_string(n + 1) + "-" + std::to_string(n + 3) +
                         ": 3 trailing blank lines"});
        // CRLF for lines 1-5, LF from line 6 on, one CR-only line (8).
        std::string mixed;
        for (int k = 0; k < n; ++k)
            mixed += lines[size_t(k)] + (k < 5 ? "\r\n" : k == 7 ? "\r" : "\n");
        c.push_back({path + " mixed line endings", path, mixed,
                     path + ":6: mixed line endings (CRLF before this line, LF here); each read as "
                            "the end of a line",
                     path + ":6: mixed line endings"});
        // The luminaire's name with a Latin-1 character (line 9 in the EULUMDAT file, 3 in IES).
        std::vector<std::string> latin = lines;
        size_t nameLine = isLdt ? 8 : 2;
        latin[nameLine] +=
            " Stra\xDF"
            "e";
        auto named = [](const PhotometricData& d) {
            EXPECT_EQ(d.name,
                      "Test luminaire Stra\xC3\x9F"
                      "e");
        };
        c.push_back({path + " Latin-1", path, join(latin),
                     path + ":" + std::to_string(nameLine + 1) +
                         ": text in Windows-1252 (Latin-1), not UTF-8; transcoded to UTF-8",
                     path + ":" + std::to_string(nameLine + 1) +
                         ": text in Windows-1252 (Latin-1), not UTF-8",
                     named});
        for (bool little : {true, false})
            for (bool bom : {true, false}) {
                std::string enc = little ? "UTF-16LE" : "UTF-16BE";
                std::string how = bom ? " with a byte-order mark" : " without a byte-order mark";
                c.push_back({path + " " + enc + how, path, utf16(join(latin, "\r\n"), little, bom),
                             path + ":1: text in " + enc + how + "; transcoded to UTF-8",
                             path + ":1: text in " + enc + how, named});
            }
    }
}

/// IES only: comments and values after the table.
void iesLeniencies(std::vector<Leniency>& c) {
    c.push_back({"ies // comment", "t.ies", iesWith([](auto& l) { l[6] += " // vertical angles"; }),
                 "t.ies:7: a '//' comment in the numeric data (not in LM-63); ignored to the end "
                 "of each line",
                 "t.ies:7: a '//' comment"});
    c.push_back({"ies values after the candela table", "t.ies",
                 iesWith([](auto& l) { l.push_back("END"); }),
                 "t.ies:11: 1 value after the candela table (from 'END'); ignored",
                 "t.ies:11: 1 value after the candela table"});
}

std::vector<Leniency> leniencies() {
    std::vector<Leniency> c;
    ldtEmptyFields(c);
    ldtRepeatedPlanes(c);
    ldtValues(c);
    textLeniencies(c);
    iesLeniencies(c);
    return c;
}

TEST(PhotometryLeniency, StrictFilesGiveNoWarnings) {
    for (const std::string& text : {join(ldtLines()), join(ldtLines(), "\r\n")}) {
        PhotometricData d = parseEulumdat(text, "t.ldt", kStrict);
        EXPECT_TRUE(d.warnings.empty());
        // 100 cd/klm at C0 gamma 0, 2000 lm: 200 cd.
        EXPECT_DOUBLE_EQ(d.intensity({0, 0, 1}), 200.0);
    }
    PhotometricData ies = parseIes(join(iesLines()), "t.ies", kStrict);
    EXPECT_TRUE(ies.warnings.empty());
    EXPECT_DOUBLE_EQ(ies.intensity({0, 0, 1}), 300.0);
    // A UTF-8 byte-order mark and UTF-8 text are the formats' own: no warning.
    std::vector<std::string> utf8 = iesLines();
    utf8[2] +=
        " Stra\xC3\x9F"
        "e";
    EXPECT_TRUE(parseIes("\xEF\xBB\xBF" + join(utf8), "t.ies", kStrict).warnings.empty());
}

TEST(PhotometryLeniency, EachLeniencyLoadsWithAWarningAndStrictRefusesIt) {
    const PhotometricData ldt = parseEulumdat(join(ldtLines()), "t.ldt", kStrict);
    const PhotometricData ies = parseIes(join(iesLines()), "t.ies", kStrict);
    for (const Leniency& c : leniencies()) {
        SCOPED_TRACE(c.name);
        PhotometricData d;
        ASSERT_NO_THROW(d = parse(c.text, c.path, kLenient));
        ASSERT_EQ(d.warnings.size(), 1u) << (d.warnings.empty() ? "" : d.warnings[0]);
        EXPECT_EQ(d.warnings[0], c.warning);
        // The same table as the strict file's (exactly: the leniencies change no number, except
        // LORL 0, which changes only the declared flux).
        const PhotometricData& same = c.path == "t.ldt" ? ldt : ies;
        EXPECT_EQ(d.vertical, same.vertical);
        EXPECT_EQ(d.horizontal, same.horizontal);
        EXPECT_EQ(d.candela, same.candela);
        EXPECT_EQ(d.lampFlux, same.lampFlux);
        c.check(d);
        std::string m = test::inputError([&] { parse(c.text, c.path, kStrict); });
        EXPECT_NE(m.find(c.refusal), std::string::npos) << m;
        EXPECT_NE(m.find("(refused by --strict)"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        EXPECT_TRUE(isValidUtf8(m)) << m;
    }
}

TEST(PhotometryLeniency, EmptyDirectRatiosColourTemperatureAndCriLoadWithWarnings) {
    // The Done-when file: all ten direct ratios, the colour temperature and the CRI
    // left empty (as some manufacturers' exporters write them).
    std::vector<std::string> l = ldtLines();
    l[29] = l[30] = "";
    for (int k = 32; k < 42; ++k) l[size_t(k)] = "";
    PhotometricData d = parseEulumdat(join(l), "t.ldt", kLenient);
    std::vector<std::string> expected = {
        "t.ldt:30: empty colour temperature of lamp set 1; left unknown",
        "t.ldt:31: empty colour rendering index of lamp set 1; left unknown",
        "t.ldt:33-42: the ten direct ratios are empty; left unknown (Candela does "
        "not use them)"};
    EXPECT_EQ(d.warnings, expected);
    EXPECT_EQ(d.candela, parseEulumdat(join(ldtLines()), "t.ldt", kStrict).candela);
    std::string m = test::inputError([&] { parseEulumdat(join(l), "t.ldt", kStrict); });
    EXPECT_EQ(m, "t.ldt:30: empty colour temperature of lamp set 1 (refused by --strict)");
    // Without the leniency the ratios would have eaten the C angles: the misleading message the
    // issue quotes. Now the C angles are read from their own lines.
    EXPECT_EQ(d.horizontal.front(), 0.0);
    EXPECT_EQ(d.horizontal.back(), 360.0);
}

TEST(PhotometryLeniency, DefaultOptionsAreLenientAndSettable) {
    std::vector<std::string> l = ldtLines();
    l[29] = "";
    EXPECT_FALSE(defaultPhotometryOptions().strict);
    EXPECT_EQ(parseEulumdat(join(l), "t.ldt").warnings.size(), 1u);
    setDefaultPhotometryOptions(kStrict);
    std::string m = test::inputError([&] { parseEulumdat(join(l), "t.ldt"); });
    setDefaultPhotometryOptions(kLenient);
    EXPECT_NE(m.find("refused by --strict"), std::string::npos) << m;
}

// ---------------------------------------------------------------------------------------------
// Defective values: errors with the file and the line in both modes.

TEST(PhotometryLeniency, DefectiveValuesAreErrors) {
    struct Defect {
        std::string path, text, message;
    };
    auto ies = [](size_t line, const std::string& text) {
        std::vector<std::string> l = iesLines();
        l[line] = text;
        return join(l);
    };
    auto ldt = [](size_t line, const std::string& text) {
        std::vector<std::string> l = ldtLines();
        l[line] = text;
        return join(l);
    };
    std::vector<Defect> defects = {
        // The IES table holding 1e308 (its flux was printed as inf).
        {"t.ies", ies(9, "310 1e308 110"),
         "t.ies:10: expected candela values (after the multipliers) of at most 1e+15 cd (no "
         "luminaire is that "
         "bright), found 1e+308 cd"},
        // A multiplier that overflows finite values.
        {"t.ies", ies(4, "1 1000 1e307 3 2 1 2 0.1 0.2 0"),
         "t.ies:9: expected candela values (after the multipliers) of at most 1e+15 cd (no "
         "luminaire is that "
         "bright), found an overflow"},
        {"t.ies", ies(8, "300 nan 100"),
         "t.ies:9: expected a finite number (candela values (2 horizontal x 3 vertical angles), "
         "value 2 of 6), found 'nan'"},
        {"t.ies", ies(8, "300 inf 100"),
         "t.ies:9: expected a finite number (candela values (2 horizontal x 3 vertical angles), "
         "value 2 of 6), found 'inf'"},
        {"t.ies", ies(8, "300 1e999 100"),
         "t.ies:9: expected a finite number (candela values (2 horizontal x 3 vertical angles), "
         "value 2 of 6), found '1e999'"},
        {"t.ies", ies(8, "300 -2 100"),
         "t.ies:9: expected non-negative candela values (horizontal angle 0, vertical angle 45), "
         "found -2"},
        {"t.ies", ies(4, "2 1e308 1 3 2 1 2 0.1 0.2 0"),
         "t.ies:5: expected a lamp flux (lamps x lumens per lamp) of at most 1e+16 lm, found an "
         "overflow"},
        {"t.ies", ies(4, "1 0 1 3 2 1 2 0.1 0.2 0"),
         "t.ies:5: expected lumens per lamp > 0, or -1 for absolute photometry, found 0"},
        {"t.ies", ies(4, "1 1000 1 3 2 1 2 1e300 0.2 0"),
         "t.ies:5: expected a luminous opening width of at most 1000 m, found 1e+300 m"},
        {"t.ldt", ldt(52, "1e300"),
         "t.ldt:53: expected intensities (cd/klm x lamp flux) of at most 1e+15 cd (no luminaire is "
         "that bright), "
         "found 2e+300 cd"},
        {"t.ldt", ldt(52, "-1"),
         "t.ldt:53: expected non-negative intensities (C90, gamma 0), found -1"},
        {"t.ldt", ldt(28, "0"),
         "t.ldt:29: expected a positive total lamp flux (sum over the lamp sets), found 0"},
        {"t.ldt", ldt(15, "2e9"),
         "t.ldt:16: expected luminous area length/diameter (mm) of at most 1000000 mm, found "
         "2e+09"},
        {"t.ldt", ldt(22, "1e300"),
         "t.ldt:23: expected a declared luminaire flux (lamp flux x LORL) of at most 1e+16 lm, "
         "found 2000 lm x 1e+298"},
    };
    for (const Defect& d : defects)
        for (const PhotometryOptions& o : {kLenient, kStrict}) {
            std::string m = test::inputError([&] { parse(d.text, d.path, o); });
            EXPECT_EQ(m, d.message);
        }
}

// ---------------------------------------------------------------------------------------------
// Messages are valid UTF-8 whatever the file name or the field's encoding.

TEST(PhotometryLeniency, MessagesAreValidUtf8) {
    const std::string latinPath = "Leuchte_\xE9t\xE9.ldt";  // "été" in Latin-1
    std::vector<std::string> l = ldtLines();
    l[29] = "";
    PhotometricData d = parseEulumdat(join(l), latinPath, kLenient);
    ASSERT_EQ(d.warnings.size(), 1u);
    EXPECT_TRUE(isValidUtf8(d.warnings[0]));
    EXPECT_EQ(d.warnings[0].rfind("Leuchte_\xC3\xA9t\xC3\xA9.ldt:30: ", 0), 0u) << d.warnings[0];
    // An error naming the file and quoting a Latin-1 field.
    l = ldtLines();
    l[1] = "\xB0";  // "°" in Latin-1 where Ityp should be
    std::string m = test::inputError([&] { parseEulumdat(join(l), latinPath, kLenient); });
    EXPECT_TRUE(isValidUtf8(m)) << m;
    EXPECT_EQ(m.find("Leuchte_\xC3\xA9t\xC3\xA9.ldt:2: "), 0u) << m;
    // The file is named once.
    EXPECT_EQ(m.find("Leuchte", 1), std::string::npos) << m;
    m = test::inputError([&] { loadPhotometry("/nonexistent/\xE9t\xE9.ies"); });
    EXPECT_TRUE(isValidUtf8(m)) << m;
}

// ---------------------------------------------------------------------------------------------
// util/TextEncoding

TEST(TextEncoding, CodePage850) {
    // The DOS code page of unflagged ZIP member names (GLDF containers): Ä ö ü ° § and a box
    // drawing character, none of them where Windows-1252 or Latin-1 has it.
    EXPECT_EQ(fromCodePage850("ldc/\x8e\x94\x81\xf8\xf5\xc9.ldt"),
              "ldc/\u00c4\u00f6\u00fc\u00b0\u00a7\u2554.ldt");
    EXPECT_EQ(fromCodePage850("plain"), "plain");
}

TEST(TextEncoding, Utf8ValidationFollowsRfc3629) {
    EXPECT_TRUE(isValidUtf8("plain ASCII"));
    EXPECT_TRUE(isValidUtf8("\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x92\xA1"));  // e acute, euro, U+1F4A1
    EXPECT_EQ(validUtf8Prefix("ab\xC0\x80"), 2u);                        // overlong NUL
    EXPECT_EQ(validUtf8Prefix("ab\xED\xA0\x80"), 2u);                    // surrogate U+D800
    EXPECT_EQ(validUtf8Prefix("ab\xF4\x90\x80\x80"), 2u);                // U+110000
    EXPECT_EQ(validUtf8Prefix("ab\xF8\x88\x80\x80\x80"), 2u);            // 5-byte form
    EXPECT_EQ(validUtf8Prefix("ab\xE2\x82"), 2u);                        // truncated
    EXPECT_EQ(validUtf8Prefix("ab\x80"), 2u);                            // lone continuation byte
    EXPECT_EQ(toValidUtf8("caf\xE9 \x80 \x81"),
              "caf\xC3\xA9 \xE2\x82\xAC \xC2\x81");  // 0x81: Latin-1
    EXPECT_EQ(toValidUtf8("caf\xC3\xA9"), "caf\xC3\xA9");
}

TEST(TextEncoding, DecodesUtf16AndLatin1AndRefusesBrokenUtf16) {
    DecodedText t = decodeText(utf16("ab\xE9\ncd", true, false), "x");
    EXPECT_EQ(t.encoding, DecodedText::Encoding::Utf16LE);
    EXPECT_FALSE(t.byteOrderMark);
    EXPECT_EQ(t.utf8, "ab\xC3\xA9\ncd");
    t = decodeText(utf16("ab", false, true), "x");
    EXPECT_EQ(t.encoding, DecodedText::Encoding::Utf16BE);
    EXPECT_EQ(t.utf8, "ab");
    t = decodeText("one\ntwo \xE9\n", "x");
    EXPECT_EQ(t.encoding, DecodedText::Encoding::Windows1252);
    EXPECT_EQ(t.firstLine, 2);
    EXPECT_EQ(t.utf8, "one\ntwo \xC3\xA9\n");
    t = decodeText("\xEF\xBB\xBFok", "x");
    EXPECT_EQ(t.encoding, DecodedText::Encoding::Utf8);
    EXPECT_EQ(t.utf8, "ok");
    std::string m = test::inputError([] {
        decodeText(std::string("\xFF\xFE"
                               "a\0b",
                               5),
                   "x.ies");
    });
    EXPECT_EQ(m, "x.ies:1: expected UTF-16LE text, found an odd number of bytes");
    m = test::inputError([] {
        decodeText(std::string("\xFF\xFE"
                               "a\0\n\0\x00\xD8x\0",
                               10),
                   "x.ies");
    });
    EXPECT_EQ(m, "x.ies:2: expected UTF-16LE text, found an invalid code unit sequence at byte 6");
}

}  // namespace
}  // namespace candela
