#pragma once
// The table of commands: each command's name, what it does in a line, its forms (and, until its
// options are declared through CommandLine, its options) and an example. `candela --help` lists
// the commands; `candela help CMD` and `candela CMD --help` print one (CommandLine::help for a
// command whose options it declares).

#include <span>
#include <string>

#include "app/commands/Commands.h"

namespace candela {

struct CommandInfo {
    const char* name;
    const char* summary;
    /// Every form of the command, each starting with its name, a form's continuation lines
    /// starting with "[", and lines of description indented by two spaces.
    const char* usage;
    const char* example;
    int (*run)(const Args&);
    /// Its options are declared through CommandLine (app/commands/Cli.h), which prints its help.
    bool declared = false;
};

std::span<const CommandInfo> commands();
/// The command called `name`, or nullptr.
const CommandInfo* findCommand(const std::string& name);
/// "candela NAME: SUMMARY", "usage:" and the forms, as the help begins.
std::string commandHeading(const CommandInfo& c);
/// The whole help of a command whose options are not declared through CommandLine.
std::string commandUsage(const CommandInfo& c);
/// The list of commands, as `candela --help` prints it.
std::string commandList();

}  // namespace candela
