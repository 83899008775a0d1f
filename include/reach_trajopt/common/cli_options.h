#pragma once
/// \file cli_options.h
/// A command-line tool's options as one table (name, argument, help text, default) and the
/// parser that reads argv against it: `--help` / `-h` prints the usage built from the table
/// (CliTool::usage), an option the table does not hold is an error naming it, an option missing
/// its value names the option. The values stay text: the tool parses them strictly
/// (cli_args.h), so "--steps 5x" names --steps.

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace reach_trajopt {

/// One row of a tool's option table.
struct CliOption {
  CliOption(std::string name, std::string argument, std::string help,
            std::string default_value = "", int arity = 1, std::string alias = "")
      : name(std::move(name)),
        argument(std::move(argument)),
        help(std::move(help)),
        default_value(std::move(default_value)),
        arity(arity),
        alias(std::move(alias)) {}

  std::string name;           ///< "--grid"
  std::string argument;       ///< the value's name in the usage ("N"); empty: a flag
  std::string help;           ///< what it does, one sentence
  std::string default_value;  ///< the value when not given (shown by --help); "": none
  int arity = 1;              ///< values after an option with an argument (--rpy r p y: 3)
  std::string alias;          ///< another accepted spelling ("--mode" for --policy); "": none
};

/// The robot tools' two shared options: --config FILE, the robot and its parameters (`help`:
/// which sections the tool reads), and --urdf FILE, a URDF instead of the config's robot.urdf.
inline CliOption configOption(std::string help, std::string default_value = "config/biped.yaml") {
  return CliOption("--config", "FILE", std::move(help), std::move(default_value));
}
inline CliOption urdfOption() {
  return CliOption("--urdf", "FILE", "URDF to use instead of the config's robot.urdf");
}

/// The parsed command line: options by their table name, and the positional arguments.
class CliArgs {
 public:
  /// True when --help or -h was given (the tool prints CliTool::usage() and exits 0).
  bool help() const { return help_; }
  /// True when the option (its table name) was given on the command line.
  bool given(const std::string& name) const;
  /// The option's value: the last one given, else the table's default ("" when none). Of an
  /// option with arity > 1, the values joined by spaces (see values()).
  std::string value(const std::string& name) const;
  /// The values of the last occurrence of an option with an argument (arity of them), or none.
  const std::vector<std::string>& values(const std::string& name) const;
  /// The arguments that are not options ("-" is one: standard input), in order.
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  friend class CliTool;
  bool help_ = false;
  std::map<std::string, std::vector<std::string>> given_;
  std::map<std::string, std::string> defaults_;
  std::vector<std::string> positional_;
};

/// A tool's name, synopsis and option table.
class CliTool {
 public:
  /// `synopsis`: the positional part of the usage line ("request.json trajectory.json");
  /// `description`: what the tool does, printed under the usage line. Option names must start
  /// with "-" and be unique (a ReachError otherwise: a programming error, caught by the test
  /// that runs every tool's --help).
  CliTool(std::string name, std::string synopsis, std::string description,
          std::vector<CliOption> options);

  /// Reads argv[1..argc-1]. An argument starting with "-" (other than "-" alone) must be an
  /// option of the table, --help or -h.
  /// \throws RequestError naming an unknown option ("unknown option '--gird' (see --help)") or
  /// an option without its value ("--grid: missing value").
  CliArgs parse(int argc, const char* const* argv) const;
  /// The --help text: usage line, description, one line per option with its default.
  std::string usage() const;
  /// The usage line alone ("usage: tool [options] synopsis").
  std::string usageLine() const;
  /// A tool's main: parses the command line, answers --help (usage on stdout, 0), else runs
  /// `body` and returns its exit status; an exception (a bad option or input) is printed as
  /// "<tool>: <what>" on stderr and gives 2.
  int run(int argc, char** argv, const std::function<int(const CliArgs&)>& body) const;
  /// The same with the exception reported by `reportError` (e.g. as a JSON answer on stdout)
  /// instead of on stderr; still exit status 2.
  int run(int argc, char** argv, const std::function<int(const CliArgs&)>& body,
          const std::function<void(const std::exception&)>& reportError) const;
  const std::string& name() const { return name_; }
  const std::vector<CliOption>& options() const { return options_; }

 private:
  const CliOption* find(const std::string& arg) const;
  std::string name_, synopsis_, description_;
  std::vector<CliOption> options_;
};

}  // namespace reach_trajopt
