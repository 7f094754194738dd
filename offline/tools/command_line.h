// command_line.h - the command-line conventions every dsn tool shares (part of libdsn_tools.a).
//
//   --flag value and --flag=value are the same; -h and --help print the tool's usage, --version its
//   name and version ("dsn-bake 1.2.0", the version of libdsn), both on stdout, exit 0; "--" ends the
//   flags.
//   A usage mistake (unknown flag, missing or malformed value, missing argument) prints one line
//   "TOOL: what is wrong (see --help)" on stderr and exits 2 (a misspelt flag gets "did you mean
//   --radius?": the flags the tool tested with is() before calling unknown() are the candidates); a failure
//   while running (unreadable input, bad asset, cannot write) prints one line "TOOL: what failed" and
//   exits 1. Nothing is left half written on failure.
//   Streams: what a run was asked for (a report, a summary line, --help, --version) goes to stdout;
//   progress, warnings and errors go to stderr, so that `tool ... > log` keeps the results alone.
//
//     int main(int argc, char **argv) {
//         return dsn::run_tool("dsn-thing", kUsage, argc, argv, [](dsn::CommandLine &arguments) {
//             while (arguments.next()) {
//                 if (arguments.is("--size")) size = dsn::parse_integer(arguments, 1, 100);
//                 else if (arguments.is("--quiet")) arguments.no_value(), quiet = true;
//                 else if (arguments.is_positional()) input = arguments.current();
//                 else arguments.unknown();
//             }
//             ... run; throw std::runtime_error on failure ...
//             return 0;
//         });
//     }
#ifndef DSN_TOOLS_COMMAND_LINE_H
#define DSN_TOOLS_COMMAND_LINE_H

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace dsn {

// A mistake in the command line: the tool exits 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class CommandLine {
  public:
    CommandLine(const char *tool, const char *usage, int argc, char **argv)
        : tool_(tool), usage_(usage), argc_(argc), argv_(argv) {}

    // Steps to the next argument; false after the last one. Answers -h, --help and --version itself
    // (they end the program with status 0 through run_tool).
    bool next();
    // The current argument: a flag's name (without "=value") or a positional argument.
    const std::string &current() const { return name_; }
    // Whether the current argument is the flag `flag` ("-o", "--size"), given as "--size 4" or "--size=4".
    // Remembers `flag` as a known one, for unknown()'s suggestion.
    bool is(const char *flag) const;
    bool is_positional() const { return positional_; }
    // The flag's value: what follows '=', else the next argument. UsageError when there is none.
    std::string value();
    // The value of a flag that names a file: UsageError when it is empty (`--report ""` would otherwise
    // quietly write nothing).
    std::string path_value();
    // For a flag that takes no value: UsageError when one was given with '='.
    void no_value() const;
    // Throws the UsageError for an unknown flag (with "did you mean --flag?" when a flag tested by is()
    // since next() is close: nearest_flag) or an extra positional argument.
    [[noreturn]] void unknown() const;

  private:
    const char *tool_, *usage_;
    int argc_;
    char **argv_;
    int index_ = 0;
    bool flags_ended_ = false, positional_ = false, has_inline_value_ = false;
    std::string name_, inline_value_;
    mutable std::vector<std::string> known_flags_; // tested by is() since the last next()
};

// Among `known` flags, the one `given` most likely misspells: the nearest by edit distance (insertions,
// deletions, substitutions, swaps of neighbours; the leading dashes and letter case ignored) when that
// distance is at most 2 and at most a third of the flag's length without its dashes, so that short flags
// ("-o") are never guessed; "" when none is that close. Ties go to the first in `known`.
std::string nearest_flag(const std::string &given, const std::vector<std::string> &known);

// A whole decimal number within [minimum, maximum] from the current flag's value; UsageError naming the
// flag otherwise.
long long parse_integer(CommandLine &arguments, long long minimum, long long maximum);
long long parse_integer(const std::string &flag, const std::string &text, long long minimum,
                        long long maximum);
// A finite decimal real number ("-1.5", "2e3"; not hexadecimal, inf or nan); UsageError otherwise.
double parse_real(const std::string &flag, const std::string &text);

// Whether `text` (a file name) ends with `suffix` (its extension, ".png").
bool ends_with(const std::string &text, const std::string &suffix);

// Runs `body` with the tool's arguments and applies the conventions above to what it throws:
// UsageError -> exit 2, any other exception -> exit 1, each as one line on stderr prefixed by `tool`.
int run_tool(const char *tool, const char *usage, int argc, char **argv,
             const std::function<int(CommandLine &)> &body);

} // namespace dsn

#endif // DSN_TOOLS_COMMAND_LINE_H
