#pragma once
// A command's command line, parsed by CLI11 (Debian's libcli11-dev): each command declares its
// arguments and options once, with their value's form and units, and the same declarations parse
// the arguments and print `candela CMD --help`, so the help cannot drift from what is accepted.
//
// Values are converted by Candela's own functions (parseInt, parseDouble, ...), so every bad value
// gets the same message naming the option ("--spp: expected an integer in 1..16777216, got
// \"x\""); CLI11 checks the shape of the line: known options, a value where one is needed, the
// arguments that must be there. What it refuses is bad usage (UsageError: exit 2 with the
// command's help); a bad value is bad input (exit 1).
//
//     std::string scene, out;
//     int spp = 64;
//     CommandLine cli("grid");
//     cli.argument("scene.json", scene, "the scene file");
//     cli.integer("--spp", spp, 1, 1 << 24, "N", "samples per point and luminaire");
//     cli.output("--out", out, "F.csv", "also write the points as CSV");
//     cli.renamed("--csv", "--out");
//     if (!cli.parse(args)) return 0;  // --help: printed

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "util/Error.h"

namespace candela {

using Args = std::vector<std::string>;

/// Bad usage caught by a CommandLine: the message, and the command's help to print after it.
class CommandUsageError : public UsageError {
  public:
    CommandUsageError(const std::string& message, std::string help)
        : UsageError(message), help_(std::move(help)) {}
    const std::string& help() const { return help_; }

  private:
    std::string help_;
};

class CommandLine {
  public:
    /// The command's name as the table of commands (app/commands/CommandTable.h) has it: its
    /// summary, forms and example head the help.
    explicit CommandLine(const std::string& command);
    ~CommandLine();
    CommandLine(const CommandLine&) = delete;
    CommandLine& operator=(const CommandLine&) = delete;

    /// Options declared after this are listed under `heading` in the help.
    void group(const std::string& heading);

    /// A positional argument (`name` is what the help calls it: "scene.json").
    void argument(const std::string& name, std::string& value, const std::string& help,
                  bool required = true);
    /// Positional arguments, one or more (or none when not required).
    void arguments(const std::string& name, std::vector<std::string>& values,
                   const std::string& help, bool required = true);

    /// An option with a value of any form: `apply` converts and stores it, throwing InputError
    /// naming the option for a bad one. `form` is the value's form in the help ("WxH", "N").
    /// Given more than once, each value is applied in turn (the last one wins unless `apply`
    /// collects them).
    void option(const std::string& name, const std::string& form, const std::string& help,
                std::function<void(const std::string&)> apply);
    /// An option whose value may be left out: `apply` gets "" then. The value must be given as
    /// NAME=VALUE or be one of `values` to be taken from the next argument.
    void optionalValue(const std::string& name, const std::vector<std::string>& values,
                       const std::string& help, std::function<void(const std::string&)> apply);
    void text(const std::string& name, std::string& value, const std::string& form,
              const std::string& help);
    /// A file or folder to write: an empty name is refused.
    void output(const std::string& name, std::string& value, const std::string& form,
                const std::string& help);
    void integer(const std::string& name, int& value, int min, int max, const std::string& form,
                 const std::string& help);
    void number(const std::string& name, double& value, double min, double max,
                const std::string& form, const std::string& help);
    /// A switch: sets `value` to `to` when given.
    void flag(const std::string& name, bool& value, const std::string& help, bool to = true);
    /// A switch that runs `apply` when given.
    void flag(const std::string& name, const std::string& help, std::function<void()> apply);
    /// `--strict`: every photometry file the command loads is read strictly (formats/Photometry.h).
    void strictPhotometry();

    /// An old spelling of `current`, accepted with a line on stderr saying what replaces it; not
    /// listed in the help.
    void renamed(const std::string& old, const std::string& current);

    /// Parses `args`. Returns false when --help was asked for (the help is printed on stdout and
    /// the command returns 0). Throws CommandUsageError for bad usage and InputError for a bad
    /// value.
    bool parse(const Args& args);
    /// Whether the option was on the command line (after parse).
    bool given(const std::string& name) const;
    /// The help text: summary, forms, arguments and options with their forms, example.
    std::string help() const;
    /// What bad usage prints after the error: the summary and the forms, and where the rest is.
    std::string shortHelp() const;

    struct Impl;

  private:
    std::unique_ptr<Impl> impl_;
};

/// Parses "WxH" (e.g. 512x512), each in 1..16384; throws InputError naming `flag`.
void parseSize(const std::string& text, int& width, int& height,
               const std::string& flag = "--size");
/// "A,B,.." as finite numbers; throws InputError naming the flag.
std::vector<float> parseNumberList(const std::string& flag, const std::string& text);
/// An integer in min..max; throws InputError "FLAG: expected an integer in MIN..MAX, got ...".
int parseInt(const std::string& flag, const std::string& text, int min, int max);
/// A finite number in min..max; throws InputError "FLAG: expected a number in MIN..MAX, got ...".
double parseDouble(const std::string& flag, const std::string& text, double min, double max);

}  // namespace candela
