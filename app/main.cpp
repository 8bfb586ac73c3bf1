// candela: the interactive lighting editor and its headless tools.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "app/commands/Cli.h"
#include "app/commands/CommandTable.h"
#include "formats/Photometry.h"
#include "util/Activity.h"
#include "util/Error.h"
#include "util/TextEncoding.h"

namespace {

/// A command's help: declared through CommandLine, the command prints it itself.
int printHelp(const candela::CommandInfo& c) {
    if (c.declared) return c.run({"--help"});
    std::fputs(candela::commandUsage(c).c_str(), stdout);
    return 0;
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
    if (!c->declared) {
        // --strict: every photometry file these commands load is read strictly (Photometry.h).
        auto strict = std::find(args.begin(), args.end(), "--strict");
        if (strict != args.end() &&
            std::string("info render probe grid surfaces polar").find(command) !=
                std::string::npos) {
            args.erase(strict);
            candela::setDefaultPhotometryOptions({.strict = true});
        }
        if (std::any_of(args.begin(), args.end(),
                        [](const std::string& a) { return a == "--help" || a == "-h"; }))
            return printHelp(*c);
    }
    try {
        return c->run(args);
    } catch (const candela::CommandUsageError& e) {
        // Bad usage: what was wrong, then the command's help; exit 2 as for an unknown command.
        std::fprintf(stderr, "candela %s: error: %s\n\n%s", command.c_str(),
                     candela::toValidUtf8(e.what()).c_str(), e.help().c_str());
        return 2;
    } catch (const candela::UsageError& e) {
        std::fprintf(stderr, "candela %s: error: %s\n\n%s", command.c_str(),
                     candela::toValidUtf8(e.what()).c_str(), candela::commandUsage(*c).c_str());
        return 2;
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
