// Helpers shared by the photometry tests (photometry_test.cpp, photometry_ldt_test.cpp): the
// shared files under tests/data/photometry, type C directions and the invariants of a table.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "TestUtil.h"
#include "formats/Photometry.h"

namespace candela::phototest {

namespace fs = std::filesystem;

inline std::string photometryDir() {
    return test::dataDir() + "/photometry";
}

inline bool isBroken(const fs::path& p) {
    std::string name = p.filename().string();
    return name == "Invalid Profile - 01.ies" || name == "Truncated Profile - 01.IES";
}

/// Every .ies / .ldt file under tests/data/photometry, sorted.
inline std::vector<fs::path> sharedFiles(bool includeBroken) {
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(photometryDir())) {
        if (!e.is_regular_file()) continue;
        std::string ext = e.path().extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(),
                       [](char c) { return char(std::tolower(c)); });
        if (ext != ".ies" && ext != ".ldt") continue;
        if (!includeBroken && isBroken(e.path())) continue;
        files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

inline glm::dvec3 dirC(double gammaDeg, double cDeg) {
    constexpr double kDeg = std::numbers::pi / 180.0;
    double g = gammaDeg * kDeg, c = cDeg * kDeg;
    return {std::sin(g) * std::cos(c), std::sin(g) * std::sin(c), std::cos(g)};
}

/// Invariants every loaded table must satisfy.
inline void expectValidTable(const PhotometricData& d, const std::string& what) {
    ASSERT_GE(d.vertical.size(), 1u) << what;
    ASSERT_GE(d.horizontal.size(), 2u) << what;
    ASSERT_EQ(d.candela.size(), d.vertical.size() * d.horizontal.size()) << what;
    for (double c : d.candela) ASSERT_TRUE(std::isfinite(c) && c >= 0.0) << what;
    for (size_t k = 1; k < d.vertical.size(); ++k)
        ASSERT_GT(d.vertical[k], d.vertical[k - 1]) << what;
    for (size_t k = 1; k < d.horizontal.size(); ++k)
        ASSERT_GT(d.horizontal[k], d.horizontal[k - 1]) << what;
    if (d.goniometer == Goniometer::C) {
        EXPECT_EQ(d.horizontal.front(), 0.0) << what;
        EXPECT_EQ(d.horizontal.back(), 360.0) << what;
        size_t nv = d.vertical.size(), last = d.horizontal.size() - 1;
        for (size_t v = 0; v < nv; ++v)  // rows at 0 and 360 are the same plane
            EXPECT_NEAR(d.candela[v], d.candela[last * nv + v], 1e-9 * (1.0 + d.candela[v]))
                << what;
    } else {
        EXPECT_GE(d.horizontal.front(), -180.0) << what;
        EXPECT_LE(d.horizontal.back(), 180.0) << what;
    }
    double flux = d.fluxFromTable();
    EXPECT_TRUE(std::isfinite(flux) && flux >= 0.0) << what;
}

}  // namespace candela::phototest
