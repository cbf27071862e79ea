// The shared command-line behaviour of every subcommand (see command_line.h).
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

int ParseCommandLine(CLI::App& app, const std::vector<std::string>& args, std::FILE* out,
                     std::FILE* err) {
  // CLI11 takes the arguments last first.
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), out);
    return kExitOk;
  } catch (const CLI::ParseError& e) {
    // The top-level parser has no name: "sketch-a-scratch: ...", not "sketch-a-scratch : ...".
    const std::string command =
        app.get_name().empty() ? "sketch-a-scratch" : "sketch-a-scratch " + app.get_name();
    std::fprintf(err, "%s: %s\n(%s --help lists the options)\n", command.c_str(), e.what(),
                 command.c_str());
    return kExitUsage;
  }
  return -1;
}

}  // namespace sas::kiosk
