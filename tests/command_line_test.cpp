// The command line's parser (app/commands/Cli.h): values that begin with "-" stay values, empty
// and left-out values reach their option, bad usage and bad values are told apart, old spellings
// still work with a line saying so, and the help lists exactly what is declared.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/commands/Cli.h"
#include "app/commands/CommandTable.h"

namespace candela {
namespace {

/// A command line with one of each kind of declaration, as a command declares them.
struct Example {
    std::string scene, out, plane, visibility = "unset";
    std::vector<std::string> panes;
    int spp = 64;
    bool noShadows = false;
    CommandLine cli{"grid"};

    Example() {
        cli.argument("scene.json", scene, "the scene file");
        cli.text("--plane", plane, "[+|-]x|y|z=VALUE", "the plane, metres");
        cli.output("--out", out, "F.csv", "the CSV to write");
        cli.renamed("--csv", "--out");
        cli.integer("--spp", spp, 1, 1024, "N", "samples per point");
        cli.option("--pane", "LIST", "one pane (repeatable)",
                   [this](const std::string& v) { panes.push_back(v); });
        cli.optionalValue("--visibility", {"embree", "bvh"}, "shadow rays",
                          [this](const std::string& v) { visibility = v; });
        cli.flag("--no-shadows", noShadows, "no shadows");
    }
};

TEST(CommandLine, ValuesThatBeginWithADashStayValues) {
    Example e;
    ASSERT_TRUE(e.cli.parse({"room.json", "--plane", "-x=2.5", "--spp", "8", "--no-shadows"}));
    EXPECT_EQ(e.scene, "room.json");
    EXPECT_EQ(e.plane, "-x=2.5");
    EXPECT_EQ(e.spp, 8);
    EXPECT_TRUE(e.noShadows);
    EXPECT_TRUE(e.cli.given("--plane"));
    EXPECT_FALSE(e.cli.given("--out"));
}

TEST(CommandLine, NameEqualsValueIsTheSameAsTwoArguments) {
    Example e;
    ASSERT_TRUE(e.cli.parse({"--spp=16", "room.json", "--plane=y=0.8"}));
    EXPECT_EQ(e.spp, 16);
    EXPECT_EQ(e.plane, "y=0.8");
    EXPECT_EQ(e.scene, "room.json");
}

TEST(CommandLine, AnEmptyOutputNameIsBadInputNotTheNextArgument) {
    Example e;
    try {
        e.cli.parse({"--out", "", "room.json"});
        FAIL() << "an empty --out was accepted";
    } catch (const CommandUsageError&) {
        FAIL() << "an empty value is a bad value (exit 1), not bad usage";
    } catch (const InputError& error) {
        EXPECT_STREQ(error.what(), "--out: expected a file name, got an empty one");
    }
    EXPECT_EQ(e.out, "");  // the scene after it was not taken as --out's value
    EXPECT_EQ(e.scene, "room.json");
}

TEST(CommandLine, AnOptionalValueIsTakenOnlyWhenItIsOneOfItsChoices) {
    Example bare;
    ASSERT_TRUE(bare.cli.parse({"--visibility", "room.json"}));
    EXPECT_EQ(bare.visibility, "");
    EXPECT_EQ(bare.scene, "room.json");
    Example chosen;
    ASSERT_TRUE(chosen.cli.parse({"--visibility", "bvh", "room.json"}));
    EXPECT_EQ(chosen.visibility, "bvh");
    EXPECT_EQ(chosen.scene, "room.json");
    Example absent;
    ASSERT_TRUE(absent.cli.parse({"room.json"}));
    EXPECT_EQ(absent.visibility, "unset");
}

TEST(CommandLine, ARepeatedOptionIsAppliedEachTimeInOrder) {
    Example e;
    ASSERT_TRUE(
        e.cli.parse({"room.json", "--pane", "a", "--spp", "2", "--pane", "b:8", "--spp", "3"}));
    EXPECT_EQ(e.panes, (std::vector<std::string>{"a", "b:8"}));
    EXPECT_EQ(e.spp, 3);  // the last one given
}

/// The message of the CommandUsageError that parsing `args` throws ("" if none).
std::string usageError(const Args& args) {
    Example e;
    try {
        e.cli.parse(args);
    } catch (const CommandUsageError& error) {
        EXPECT_NE(error.help().find("usage:"), std::string::npos) << error.help();
        return error.what();
    }
    return "";
}

TEST(CommandLine, BadUsageNamesWhatWasWrong) {
    EXPECT_EQ(usageError({"room.json", "--bogus"}), "unknown option --bogus");
    EXPECT_EQ(usageError({"room.json", "--bogus=3"}), "unknown option --bogus");
    EXPECT_EQ(usageError({"room.json", "other.json"}), "unexpected argument other.json");
    EXPECT_EQ(usageError({"--spp", "8"}), "missing scene.json (the scene file)");
    EXPECT_EQ(usageError({"room.json", "--spp"}), "--spp: expected N after it");
}

TEST(CommandLine, ABadValueIsBadInputNamingItsOption) {
    Example e;
    try {
        e.cli.parse({"room.json", "--spp", "0"});
        FAIL() << "--spp 0 was accepted";
    } catch (const CommandUsageError&) {
        FAIL() << "a bad value is bad input (exit 1), not bad usage";
    } catch (const InputError& error) {
        EXPECT_STREQ(error.what(), "--spp: expected an integer in 1..1024, got \"0\"");
    }
}

TEST(CommandLine, AnOldSpellingWorksAndSaysWhatReplacesIt) {
    Example e;
    testing::internal::CaptureStderr();
    ASSERT_TRUE(e.cli.parse({"room.json", "--csv", "points.csv"}));
    std::string said = testing::internal::GetCapturedStderr();
    EXPECT_EQ(e.out, "points.csv");
    EXPECT_NE(said.find("--csv is now called --out"), std::string::npos) << said;
    EXPECT_TRUE(e.cli.given("--out"));
}

TEST(CommandLine, HelpIsPrintedInsteadOfRunningAndListsEveryDeclaration) {
    Example e;
    testing::internal::CaptureStdout();
    bool run = e.cli.parse({"room.json", "--help"});
    std::string printed = testing::internal::GetCapturedStdout();
    EXPECT_FALSE(run);
    EXPECT_EQ(printed, e.cli.help());
    for (const char* shown :
         {"scene.json", "--plane [+|-]x|y|z=VALUE", "--out F.csv", "--spp N", "--pane LIST",
          "--visibility [embree|bvh]", "--no-shadows", "-h, --help", "usage:", "example:"})
        EXPECT_NE(printed.find(shown), std::string::npos) << shown << " in\n" << printed;
    // The old spelling is accepted but not offered.
    EXPECT_EQ(printed.find("--csv"), std::string::npos) << printed;
    // Its heading and example are the table's.
    EXPECT_NE(printed.find(findCommand("grid")->example), std::string::npos);
}

}  // namespace
}  // namespace candela
