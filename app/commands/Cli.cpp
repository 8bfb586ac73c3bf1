// A command's command line through CLI11 (app/commands/Cli.h).
//
// CLI11 recognises the options and arguments, counts them and finds what is left over; the
// declarations here keep what CLI11 does not: each value's form and conversion, the headings of
// the help, the old spellings. Before CLI11 sees the line, every value an option takes is joined to
// it as NAME=VALUE, so a value that begins with "-" (a plane "-x=2.5", an extent "-2,-2,2,2") is
// the option's value as it always was, not an option of its own.
#include "app/commands/Cli.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/commands/CommandTable.h"
#include "formats/Photometry.h"

namespace candela {

namespace {

/// Where the help's descriptions begin, and the width they wrap to.
constexpr size_t kHelpColumn = 28, kHelpWidth = 100;

enum class Kind { Positional, Value, OptionalValue, Flag };

struct Declaration {
    Kind kind;
    std::string name;  ///< "--spp"; for a positional, what the help calls it ("scene.json").
    std::string form;  ///< The value's form in the help ("N", "WxH").
    std::string help;
    std::string group;
    bool required = false, many = false;
    std::vector<std::string> values;  ///< An optional value's choices.
    std::function<void(const std::string&)> apply;
    CLI::Option* option = nullptr;
};

/// `text` wrapped at kHelpWidth, every line after the first indented to kHelpColumn.
std::string wrapped(const std::string& text) {
    std::string out, line;
    size_t width = kHelpWidth - kHelpColumn;
    size_t at = 0;
    while (at < text.size()) {
        size_t space = text.find(' ', at);
        std::string word = text.substr(at, space == std::string::npos ? space : space - at);
        at = space == std::string::npos ? text.size() : space + 1;
        if (!line.empty() && line.size() + 1 + word.size() > width) {
            out += line + "\n" + std::string(kHelpColumn, ' ');
            line.clear();
        }
        line += (line.empty() ? "" : " ") + word;
    }
    return out + line;
}

}  // namespace

struct CommandLine::Impl {
    const CommandInfo* info = nullptr;
    std::string command;
    CLI::App app;
    std::vector<Declaration> declarations;
    std::vector<std::pair<std::string, std::string>> renamed;  ///< Old spelling, current one.
    std::string group = "options";
    int positionals = 0;
    /// Optional values left out, applied as "" (CLI11 does not see them).
    std::vector<const Declaration*> direct;

    Declaration& declare(Declaration d) {
        d.group = d.kind == Kind::Positional ? "arguments" : group;
        if (std::any_of(declarations.begin(), declarations.end(),
                        [&](const Declaration& e) { return e.name == d.name; }))
            throw std::logic_error("CommandLine: " + d.name + " declared twice");
        // CLI11 names a positional by an identifier of its own; the help uses ours.
        std::string cliName =
            d.kind == Kind::Positional ? "argument" + std::to_string(positionals++) : d.name;
        switch (d.kind) {
            case Kind::Flag:
                d.option = app.add_flag(cliName);
                break;
            case Kind::Positional:
                d.option = app.add_option(cliName);
                // CLI11 gives a positional more values than its minimum only with extra arguments
                // allowed.
                if (d.many)
                    d.option->expected(0, CLI::detail::expected_max_vector_size)
                        ->allow_extra_args(true);
                break;
            case Kind::Value:
                d.option = app.add_option(cliName);
                break;
            case Kind::OptionalValue:
                d.option = app.add_option(cliName)->expected(0, 1);
                break;
        }
        d.option->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
        declarations.push_back(std::move(d));
        return declarations.back();
    }

    const Declaration* find(const std::string& name) const {
        for (const Declaration& d : declarations)
            if (d.kind != Kind::Positional && d.name == name) return &d;
        return nullptr;
    }

    [[noreturn]] void usage(const std::string& message, const CommandLine& cli) const {
        throw CommandUsageError(message, cli.shortHelp());
    }
};

CommandLine::CommandLine(const std::string& command) : impl_(std::make_unique<Impl>()) {
    impl_->command = command;
    impl_->info = findCommand(command);
    impl_->app.name("candela " + command);
    impl_->app.set_help_flag("-h,--help");
    // What CLI11 does not recognise is left for parse() to name in Candela's words.
    impl_->app.allow_extras(true);
}

CommandLine::~CommandLine() = default;

void CommandLine::group(const std::string& heading) {
    impl_->group = heading;
}

void CommandLine::argument(const std::string& name, std::string& value, const std::string& help,
                           bool required) {
    Declaration d;
    d.kind = Kind::Positional;
    d.name = name;
    d.help = help;
    d.required = required;
    d.apply = [&value](const std::string& v) { value = v; };
    impl_->declare(std::move(d));
}

void CommandLine::arguments(const std::string& name, std::vector<std::string>& values,
                            const std::string& help, bool required) {
    Declaration d;
    d.kind = Kind::Positional;
    d.name = name;
    d.help = help;
    d.required = required;
    d.many = true;
    d.apply = [&values](const std::string& v) { values.push_back(v); };
    impl_->declare(std::move(d));
}

void CommandLine::option(const std::string& name, const std::string& form, const std::string& help,
                         std::function<void(const std::string&)> apply) {
    Declaration d;
    d.kind = Kind::Value;
    d.name = name;
    d.form = form;
    d.help = help;
    d.apply = std::move(apply);
    impl_->declare(std::move(d));
}

void CommandLine::optionalValue(const std::string& name, const std::vector<std::string>& values,
                                const std::string& help,
                                std::function<void(const std::string&)> apply) {
    std::string form;
    for (const std::string& v : values) form += (form.empty() ? "" : "|") + v;
    Declaration d;
    d.kind = Kind::OptionalValue;
    d.name = name;
    d.form = "[" + form + "]";
    d.help = help;
    d.values = values;
    d.apply = std::move(apply);
    impl_->declare(std::move(d));
}

void CommandLine::text(const std::string& name, std::string& value, const std::string& form,
                       const std::string& help) {
    option(name, form, help, [&value](const std::string& v) { value = v; });
}

void CommandLine::output(const std::string& name, std::string& value, const std::string& form,
                         const std::string& help) {
    option(name, form, help, [&value, name](const std::string& v) {
        // `--out ""` would otherwise write nothing and exit 0.
        if (v.empty()) throw InputError(name + ": expected a file name, got an empty one");
        value = v;
    });
}

void CommandLine::integer(const std::string& name, int& value, int min, int max,
                          const std::string& form, const std::string& help) {
    option(name, form, help,
           [&value, name, min, max](const std::string& v) { value = parseInt(name, v, min, max); });
}

void CommandLine::number(const std::string& name, double& value, double min, double max,
                         const std::string& form, const std::string& help) {
    option(name, form, help, [&value, name, min, max](const std::string& v) {
        value = parseDouble(name, v, min, max);
    });
}

void CommandLine::flag(const std::string& name, bool& value, const std::string& help, bool to) {
    flag(name, help, [&value, to] { value = to; });
}

void CommandLine::flag(const std::string& name, const std::string& help,
                       std::function<void()> apply) {
    Declaration d;
    d.kind = Kind::Flag;
    d.name = name;
    d.help = help;
    d.apply = [apply = std::move(apply)](const std::string&) { apply(); };
    impl_->declare(std::move(d));
}

void CommandLine::strictPhotometry() {
    flag("--strict",
         "refuse photometry files that need a leniency (empty EULUMDAT fields, Latin-1 or UTF-16 "
         "text, mixed line endings) instead of loading them with a warning",
         [] { setDefaultPhotometryOptions({.strict = true}); });
}

void CommandLine::renamed(const std::string& old, const std::string& current) {
    impl_->renamed.emplace_back(old, current);
}

bool CommandLine::given(const std::string& name) const {
    for (const Declaration& d : impl_->declarations)
        if (d.name == name)
            return d.option->count() > 0 ||
                   std::find(impl_->direct.begin(), impl_->direct.end(), &d) != impl_->direct.end();
    throw std::logic_error("CommandLine: " + name + " was not declared");
}

bool CommandLine::parse(const Args& args) {
    Impl& m = *impl_;
    // Old spellings become the current ones, each with a line saying so.
    Args line;
    for (const std::string& a : args) {
        std::string arg = a;
        for (const auto& [old, current] : m.renamed) {
            if (arg == old || arg.rfind(old + "=", 0) == 0) {
                std::fprintf(stderr,
                             "candela %s: %s is now called %s (the old name will stop working "
                             "in the next release)\n",
                             m.command.c_str(), old.c_str(), current.c_str());
                arg = current + arg.substr(old.size());
            }
        }
        line.push_back(arg);
    }
    // Each value joined to its option (see the top of the file). CLI11 reads "NAME=" as NAME
    // followed by a value still to come, so an empty value stays an argument of its own, and an
    // optional value left out goes to the option directly.
    Args joined;
    m.direct.clear();
    for (size_t i = 0; i < line.size(); ++i) {
        const Declaration* d = m.find(line[i]);
        size_t equals = line[i].find('=');
        if (!d && line[i].rfind("--", 0) == 0 && equals != std::string::npos) {
            const Declaration* named = m.find(line[i].substr(0, equals));
            if (named && named->kind == Kind::Flag)
                m.usage(named->name + " takes no value (got \"" + line[i] + "\")", *this);
        }
        if (d && d->kind == Kind::Value) {
            if (i + 1 >= line.size())
                m.usage(d->name + ": expected " + d->form + " after it", *this);
            if (line[i + 1].empty()) {
                // An empty value as an argument of its own, in its place among the others.
                joined.push_back(line[i]);
                joined.push_back("");
            } else {
                joined.push_back(line[i] + "=" + line[i + 1]);
            }
            ++i;
        } else if (d && d->kind == Kind::OptionalValue) {
            bool takes = i + 1 < line.size() && std::find(d->values.begin(), d->values.end(),
                                                          line[i + 1]) != d->values.end();
            if (takes) {
                joined.push_back(line[i] + "=" + line[i + 1]);
                ++i;
            } else {
                m.direct.push_back(d);
            }
        } else {
            joined.push_back(line[i]);
        }
    }
    std::reverse(joined.begin(), joined.end());
    try {
        m.app.parse(joined);
    } catch (const CLI::CallForHelp&) {
        std::fputs(help().c_str(), stdout);
        return false;
    } catch (const CLI::ParseError& e) {
        m.usage(e.what(), *this);
    }
    std::vector<std::string> left = m.app.remaining();
    if (!left.empty()) {
        const std::string& a = left.front();
        m.usage(a.size() > 1 && a[0] == '-' ? "unknown option " + a.substr(0, a.find('='))
                                            : "unexpected argument " + a,
                *this);
    }
    for (const Declaration& d : m.declarations)
        if (d.required && !given(d.name)) m.usage("missing " + d.name + " (" + d.help + ")", *this);
    // Values converted in the order the options were declared, each as often as it was given.
    for (const Declaration& d : m.declarations) {
        if (d.kind == Kind::Flag) {
            if (d.option->count() > 0) d.apply("");
            continue;
        }
        for (const std::string& v : d.option->results()) d.apply(v);
        for (const Declaration* to : m.direct)
            if (to == &d) d.apply("");
    }
    return true;
}

std::string CommandLine::shortHelp() const {
    const Impl& m = *impl_;
    return (m.info ? commandHeading(*m.info) : "candela " + m.command + "\n") + "\n(candela " +
           m.command + " --help lists every option)\n";
}

std::string CommandLine::help() const {
    const Impl& m = *impl_;
    std::string out = m.info ? commandHeading(*m.info) : "candela " + m.command + "\n";
    std::string group;
    auto entry = [&](const std::string& left, const std::string& text) {
        std::string l = "  " + left;
        out += l.size() + 2 <= kHelpColumn ? l + std::string(kHelpColumn - l.size(), ' ')
                                           : l + "\n" + std::string(kHelpColumn, ' ');
        out += wrapped(text) + "\n";
    };
    for (const Declaration& d : m.declarations) {
        if (d.group != group) {
            group = d.group;
            out += "\n" + group + ":\n";
        }
        std::string left = d.name;
        if (d.kind == Kind::Positional && d.many) left += "...";
        if (!d.form.empty()) left += " " + d.form;
        entry(left, d.help + (d.kind == Kind::Positional && !d.required ? " (optional)" : ""));
    }
    if (group != "options") out += "\n";
    entry("-h, --help", "this help");
    if (m.info) out += std::string("\nexample:\n  ") + m.info->example + "\n";
    return out;
}

void parseSize(const std::string& text, int& width, int& height, const std::string& flag) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 1 ||
        h < 1 || w > 16384 || h > 16384)
        throw InputError(flag + ": expected WIDTHxHEIGHT with each in 1..16384, got \"" + text +
                         "\"");
    width = w;
    height = h;
}

std::vector<float> parseNumberList(const std::string& flag, const std::string& text) {
    std::vector<float> values;
    size_t start = 0;
    while (true) {
        size_t comma = text.find(',', start);
        std::string item = text.substr(start, comma - start);
        size_t used = 0;
        double v = 0.0;
        try {
            v = std::stod(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (item.empty() || used != item.size() || !std::isfinite(v))
            throw InputError(flag + ": expected comma-separated finite numbers, got \"" + text +
                             "\"");
        values.push_back(float(v));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return values;
}

int parseInt(const std::string& flag, const std::string& text, int min, int max) {
    try {
        size_t used = 0;
        long v = std::stol(text, &used);
        if (used == text.size() && v >= min && v <= max) return int(v);
    } catch (const std::exception&) {
    }
    throw InputError(flag + ": expected an integer in " + std::to_string(min) + ".." +
                     std::to_string(max) + ", got \"" + text + "\"");
}

double parseDouble(const std::string& flag, const std::string& text, double min, double max) {
    try {
        size_t used = 0;
        double v = std::stod(text, &used);
        if (used == text.size() && std::isfinite(v) && v >= min && v <= max) return v;
    } catch (const std::exception&) {
    }
    char range[96];
    std::snprintf(range, sizeof range, "a number in %g..%g", min, max);
    throw InputError(flag + ": expected " + range + ", got \"" + text + "\"");
}

}  // namespace candela
