// command_line.cpp - the shared argument parsing and exit conventions of the tools (command_line.h).
#include "command_line.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>

#include "dsn/dsn.h"

namespace dsn {
namespace {

// Thrown by --help and --version once they have printed: the tool ends with status 0.
struct FinishedEarly {};

} // namespace

bool CommandLine::next() {
    if (++index_ >= argc_) return false;
    const std::string argument = argv_[index_];
    has_inline_value_ = false;
    inline_value_.clear();
    positional_ = flags_ended_ || argument.size() < 2 || argument[0] != '-';
    name_ = argument;
    known_flags_.clear();
    if (positional_) return true;
    if (argument == "--") {
        flags_ended_ = true;
        return next();
    }
    const size_t equals = argument.find('=');
    if (argument.compare(0, 2, "--") == 0 && equals != std::string::npos) {
        name_ = argument.substr(0, equals);
        inline_value_ = argument.substr(equals + 1);
        has_inline_value_ = true;
    }
    if (name_ == "-h" || name_ == "--help") {
        no_value();
        std::fputs(usage_, stdout);
        throw FinishedEarly();
    }
    if (name_ == "--version") {
        no_value();
        std::printf("%s %s\n", tool_, dsn_version());
        throw FinishedEarly();
    }
    return true;
}

bool CommandLine::is(const char *flag) const {
    if (positional_) return false;
    known_flags_.push_back(flag);
    return name_ == flag;
}

std::string CommandLine::value() {
    if (has_inline_value_) return inline_value_;
    if (index_ + 1 >= argc_) throw UsageError(name_ + " needs a value");
    return argv_[++index_];
}

std::string CommandLine::path_value() {
    const std::string path = value();
    if (path.empty()) throw UsageError(name_ + " needs a file name, not an empty one");
    return path;
}

void CommandLine::no_value() const {
    if (has_inline_value_) throw UsageError(name_ + " takes no value");
}

void CommandLine::unknown() const {
    if (positional_) throw UsageError("unexpected argument '" + name_ + "'");
    std::vector<std::string> candidates = known_flags_;
    candidates.push_back("--help"); // answered by next() itself, never tested with is()
    candidates.push_back("--version");
    const std::string suggestion = nearest_flag(name_, candidates);
    throw UsageError("unknown flag " + name_ +
                     (suggestion.empty() ? "" : ": did you mean " + suggestion + "?"));
}

namespace {

std::string flag_word(const std::string &flag) {
    std::string word = flag.substr(std::min(flag.find_first_not_of('-'), flag.size()));
    for (char &c : word) c = char(std::tolower(static_cast<unsigned char>(c)));
    return word;
}

// The edit distance with adjacent transpositions counted as one edit (optimal string alignment), so
// that "--szie" is one edit from "--size".
size_t edit_distance(const std::string &a, const std::string &b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); i++) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); j++) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); i++)
        for (size_t j = 1; j <= b.size(); j++) {
            d[i][j] = std::min(
                {d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

} // namespace

std::string nearest_flag(const std::string &given, const std::vector<std::string> &known) {
    const std::string word = flag_word(given);
    std::string best;
    size_t best_distance = 3; // farther than any suggestion
    for (const std::string &flag : known) {
        const std::string known_word = flag_word(flag);
        const size_t distance = edit_distance(word, known_word);
        if (distance < best_distance && 3 * distance <= known_word.size())
            best = flag, best_distance = distance;
    }
    return best;
}

long long parse_integer(const std::string &flag, const std::string &text, long long minimum,
                        long long maximum) {
    char *end = nullptr;
    errno = 0;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE ||
        !(text[0] == '-' || (text[0] >= '0' && text[0] <= '9')))
        throw UsageError(flag + " needs a whole number, not '" + text + "'");
    if (value < minimum || value > maximum)
        throw UsageError(flag.substr(flag.find_first_not_of('-')) + " " + text + " out of range " +
                         std::to_string(minimum) + ".." + std::to_string(maximum));
    return value;
}

long long parse_integer(CommandLine &arguments, long long minimum, long long maximum) {
    const std::string flag = arguments.current();
    return parse_integer(flag, arguments.value(), minimum, maximum);
}

// Decimal only, like parse_integer: strtod alone would also take "0x10" (16), "inf" and "nan".
bool is_decimal_real(const std::string &text) {
    size_t at = 0, digits = 0;
    if (at < text.size() && (text[at] == '-' || text[at] == '+')) at++;
    for (; at < text.size() && text[at] >= '0' && text[at] <= '9'; at++) digits++;
    if (at < text.size() && text[at] == '.')
        for (at++; at < text.size() && text[at] >= '0' && text[at] <= '9'; at++) digits++;
    if (digits == 0) return false;
    if (at < text.size() && (text[at] == 'e' || text[at] == 'E')) {
        at++;
        if (at < text.size() && (text[at] == '-' || text[at] == '+')) at++;
        size_t exponent_digits = 0;
        for (; at < text.size() && text[at] >= '0' && text[at] <= '9'; at++) exponent_digits++;
        if (exponent_digits == 0) return false;
    }
    return at == text.size();
}

double parse_real(const std::string &flag, const std::string &text) {
    char *end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (!is_decimal_real(text) || *end != '\0' || !std::isfinite(value))
        throw UsageError(flag + " needs a finite number, not '" + text + "'");
    return value;
}

int run_tool(const char *tool, const char *usage, int argc, char **argv,
             const std::function<int(CommandLine &)> &body) {
    CommandLine arguments(tool, usage, argc, argv);
    try {
        return body(arguments);
    } catch (const FinishedEarly &) {
        return 0;
    } catch (const UsageError &error) {
        std::fprintf(stderr, "%s: %s (see --help)\n", tool, error.what());
        return 2;
    } catch (const std::bad_alloc &) {
        std::fprintf(stderr, "%s: out of memory\n", tool);
        return 1;
    } catch (const std::exception &error) {
        std::fprintf(stderr, "%s: %s\n", tool, error.what());
        return 1;
    }
}

bool ends_with(const std::string &text, const std::string &suffix) {
    return text.size() >= suffix.size() &&
           text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

} // namespace dsn
