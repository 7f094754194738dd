// fuzz_command_line.cpp - arbitrary bytes, split at NUL into arguments -> the tools' shared command-line
// parsing (command_line.h) with flags of each kind: whatever the arguments, parsing ends in a value, a
// UsageError or --help/--version (exit 0), and a parsed number lies within its range.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "fuzz_input.h"
#include "offline/tools/command_line.h"

extern "C" int LLVMFuzzerInitialize(int *, char ***) {
    // --help prints the usage on stdout: keep the fuzzer's output readable.
    std::FILE *ignored = std::freopen("/dev/null", "w", stdout);
    (void)ignored;
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    std::vector<std::string> arguments = {"dsn-fuzz"};
    std::string current;
    for (size_t i = 0; i < size && arguments.size() < 64; i++) {
        if (data[i] == 0) {
            arguments.push_back(current);
            current.clear();
        } else {
            current += char(data[i]);
        }
    }
    arguments.push_back(current);
    std::vector<char *> argv;
    for (std::string &argument : arguments) argv.push_back(&argument[0]);
    argv.push_back(nullptr);
    const int status = dsn::run_tool(
        "dsn-fuzz", "usage: dsn-fuzz\n", int(arguments.size()), argv.data(), [](dsn::CommandLine &line) {
            while (line.next()) {
                if (line.is("--radius")) {
                    const long long radius = dsn::parse_integer(line, 1, 127);
                    fuzz_require(radius >= 1 && radius <= 127);
                } else if (line.is("--seed")) {
                    const long long seed = dsn::parse_integer(line, 0, 4294967295ll);
                    fuzz_require(seed >= 0 && seed <= 4294967295ll);
                } else if (line.is("--scale")) {
                    const std::string flag = line.current();
                    fuzz_require(std::isfinite(dsn::parse_real(flag, line.value())));
                } else if (line.is("-o") || line.is("--output")) {
                    line.value();
                } else if (line.is("--quiet")) {
                    line.no_value();
                } else if (!line.is_positional()) {
                    line.unknown();
                }
            }
            return 0;
        });
    fuzz_require(status == 0 || status == 2);
    return 0;
}
