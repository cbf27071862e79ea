#pragma once
// The one argument parser of every subcommand: CLI11 (Debian's libcli11-dev), wrapped so that all
// subcommands behave alike: `--help` prints the usage on stdout and exits 0, a usage error prints
// one line naming the option plus a pointer to --help on stderr and exits 2, and a runtime error
// exits 1 (kExit* below, documented in the man page's EXIT STATUS).

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

}  // namespace sas::kiosk
