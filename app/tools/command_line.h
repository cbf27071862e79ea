#pragma once
// The one argument parser of every program the build makes and of every sketch-a-scratch
// subcommand: CLI11 (Debian's libcli11-dev), wrapped so that all behave alike: `--help` prints
// the usage on stdout and exits 0, a usage error prints one line naming the option plus a pointer
// to --help on stderr and exits 2, and a runtime error exits 1 (kExit* below, documented in the
// man page's EXIT STATUS). An unknown long option is named before anything that is missing.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

namespace sas::kiosk {

inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntimeError = 1;
inline constexpr int kExitUsage = 2;

// A floating-point option that must be a finite number within [min, max] (CLI11's own Range lets
// "nan" through).
CLI::Option* AddNumberOption(CLI::App& app, const std::string& name, double& target, double min,
                             double max, const std::string& description);

// Parses `args` (after the subcommand's name). Returns -1 when the caller should go on, else the
// exit code to return: kExitOk after --help (usage printed to `out`), kExitUsage after a bad
// command line (message to `err`, prefixed by "sketch-a-scratch <command>: ").
int ParseCommandLine(CLI::App& app, const std::vector<std::string>& args, std::FILE* out,
                     std::FILE* err);

// The same for a program of its own (a tool or test driver beside sketch-a-scratch): parses
// argv[1..], usage on stdout, errors on stderr prefixed by the app's name (argv[0] when it has
// none). `if (const int code = ParseProgramCommandLine(app, argc, argv); code >= 0) return code;`
int ParseProgramCommandLine(CLI::App& app, int argc, const char* const* argv);

}  // namespace sas::kiosk
