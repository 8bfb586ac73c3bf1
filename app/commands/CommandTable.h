#pragma once
// The table of commands: each command's name, what it does in a line, its forms and an example.
// `candela --help` lists the commands; `candela help CMD` and `candela CMD --help` print one, with
// the options the command declares through CommandLine (app/commands/Cli.h).

#include <span>
#include <string>

#include "app/commands/Commands.h"

namespace candela {

struct CommandInfo {
    const char* name;
    const char* summary;
    /// Every form of the command, each starting with its name, a form's continuation lines
    /// starting with "[", and lines of description indented by two spaces; the options are the
    /// command's declarations.
    const char* usage;
    const char* example;
    int (*run)(const Args&);
};

std::span<const CommandInfo> commands();
/// The command called `name`, or nullptr.
const CommandInfo* findCommand(const std::string& name);
/// "candela NAME: SUMMARY", "usage:" and the forms, as the help begins.
std::string commandHeading(const CommandInfo& c);
/// The list of commands, as `candela --help` prints it.
std::string commandList();

}  // namespace candela
