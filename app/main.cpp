// candela: the interactive lighting editor and its headless tools.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "app/commands/Cli.h"
#include "app/commands/CommandTable.h"
#include "calculation/SettingError.h"
#include "util/Activity.h"
#include "util/Error.h"
#include "util/TextEncoding.h"

namespace {

/// The option that gives a calculation's setting (calculation/SettingError.h).
std::string optionFor(const std::string& setting) {
    if (setting == "environment technique") return "--env-technique";
    return "--" + setting;  // technique, spacing, extent
}

/// A command's help: the command prints it from its declarations (app/commands/Cli.h).
int printHelp(const candela::CommandInfo& c) {
    return c.run({"--help"});
}

}  // namespace

int main(int argc, char** argv) {
    using candela::commandList;
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
        std::fputs(commandList().c_str(), argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    if (!std::strcmp(argv[1], "--version")) {
        std::printf("candela %s (commit %s)\n", CANDELA_VERSION, CANDELA_COMMIT);
        return 0;
    }
    if (!std::strcmp(argv[1], "help")) {
        if (argc < 3) {
            std::fputs(commandList().c_str(), stdout);
            return 0;
        }
        const candela::CommandInfo* c = candela::findCommand(argv[2]);
        if (!c) {
            std::fprintf(stderr, "candela: unknown command \"%s\"\n%s", argv[2],
                         commandList().c_str());
            return 2;
        }
        return printHelp(*c);
    }
    std::string command = argv[1];
    candela::Args args(argv + 2, argv + argc);
    const candela::CommandInfo* c = candela::findCommand(command);
    if (!c) {
        std::fprintf(stderr, "candela: unknown command \"%s\"\n%s", command.c_str(),
                     commandList().c_str());
        return 2;
    }
    try {
        return c->run(args);
    } catch (const candela::CommandUsageError& e) {
        // Bad usage: what was wrong, then the command's help; exit 2 as for an unknown command.
        std::fprintf(stderr, "candela %s: error: %s\n\n%s", command.c_str(),
                     candela::toValidUtf8(e.what()).c_str(), e.help().c_str());
        return 2;
    } catch (const candela::SettingError& e) {
        // A calculation's setting, worded as the command line gives it.
        std::fprintf(stderr, "candela %s: error: %s: %s\n", command.c_str(),
                     optionFor(e.setting()).c_str(), candela::toValidUtf8(e.problem()).c_str());
        return 1;
    } catch (const std::bad_alloc&) {
        // Says what it was doing (util/Activity.h) instead of "std::bad_alloc".
        std::string what = candela::toValidUtf8(candela::takeFailedActivity());
        std::fprintf(stderr,
                     "candela %s: error: out of memory%s%s (docs/limits.md lists what Candela "
                     "bounds)\n",
                     command.c_str(), what.empty() ? "" : " while ", what.c_str());
        return 1;
    } catch (const std::exception& e) {
        // One line of valid UTF-8 whatever the message quotes (file names, fields in Latin-1).
        std::string message = candela::toValidUtf8(e.what());
        std::replace(message.begin(), message.end(), '\n', ' ');
        std::replace(message.begin(), message.end(), '\r', ' ');
        std::fprintf(stderr, "candela %s: error: %s\n", command.c_str(), message.c_str());
        return 1;
    }
}
