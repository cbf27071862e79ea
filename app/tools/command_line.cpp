// The shared command-line behaviour of every program and subcommand (see command_line.h).
#include "tools/command_line.h"

#include <cmath>
#include <sstream>

namespace sas::kiosk {

CLI::Option* AddNumberOption(CLI::App& app, const std::string& name, double& target, double min,
                             double max, const std::string& description) {
  std::ostringstream range;
  range << "[" << min << ", " << max << "]";
  const std::string range_text = range.str();
  CLI::Validator finite(
      [min, max, range_text](std::string& text) -> std::string {
        std::size_t used = 0;
        double value = 0.0;
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != text.size() || !std::isfinite(value)) return "'" + text + "' is not a number";
        if (value < min || value > max) return text + " is out of range " + range_text;
        return "";
      },
      "NUMBER in " + range_text);
  return app.add_option(name, target, description)->check(finite);
}

namespace {

// CLI11 checks required options and positionals before it looks for unknown ones, so
// `prog --typo` would complain about what is missing instead of the typo. The first long option
// that neither the app nor any of its subcommands knows (none after "--").
std::string UnknownLongOption(const CLI::App& app, const std::vector<std::string>& args) {
  if (app.get_allow_extras()) return "";
  const auto known = [](const CLI::App& where, const std::string& name, const auto& self) -> bool {
    if (where.get_option_no_throw(name) != nullptr) return true;
    for (const CLI::App* sub : where.get_subcommands([](const CLI::App*) { return true; })) {
      if (self(*sub, name, self)) return true;
    }
    return false;
  };
  for (const std::string& arg : args) {
    if (arg == "--") break;
    if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) continue;
    const std::string name = arg.substr(0, arg.find('='));
    if (!known(app, name, known)) return name;
  }
  return "";
}

// `command` prefixes the error messages; `help_prefix` goes before the app's name in the usage.
int Parse(CLI::App& app, const std::vector<std::string>& args, const std::string& command,
          const std::string& help_prefix, std::FILE* out, std::FILE* err) {
  // CLI11 takes the arguments last first.
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    if (const std::string unknown = UnknownLongOption(app, args); !unknown.empty()) {
      throw CLI::ExtrasError({unknown});
    }
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help(help_prefix).c_str(), out);
    return kExitOk;
  } catch (const CLI::ParseError& e) {
    std::fprintf(err, "%s: %s\n(%s --help lists the options)\n", command.c_str(), e.what(),
                 command.c_str());
    return kExitUsage;
  }
  return -1;
}

}  // namespace

int ParseCommandLine(CLI::App& app, const std::vector<std::string>& args, std::FILE* out,
                     std::FILE* err) {
  // The top-level parser has no name: "sketch-a-scratch: ...", not "sketch-a-scratch : ...".
  const std::string command =
      app.get_name().empty() ? "sketch-a-scratch" : "sketch-a-scratch " + app.get_name();
  // The usage line names the program: "sketch-a-scratch [OPTIONS]", "sketch-a-scratch demo ...".
  std::string help_prefix;
  if (app.get_name().empty()) {
    app.name("sketch-a-scratch");
  } else {
    help_prefix = "sketch-a-scratch";
  }
  return Parse(app, args, command, help_prefix, out, err);
}

int ParseProgramCommandLine(CLI::App& app, int argc, const char* const* argv) {
  std::string name = app.get_name();
  if (name.empty() && argc > 0) {
    name = argv[0];
    name = name.substr(name.find_last_of('/') + 1);
    app.name(name);  // the usage line names the program too
  }
  const std::vector<std::string> args(argv + (argc > 0 ? 1 : 0), argv + argc);
  return Parse(app, args, name, "", stdout, stderr);
}

}  // namespace sas::kiosk
