/// parameter_table: the parameter table of every config section (docs/parameters.md), from
/// the field tables of the config structs (include/reach_trajopt/common/config_fields.h).
///
///   parameter_table > docs/parameters.md    regenerate the file
///
/// Exit status: 0, or 2 on an error. test_parameter_table fails when the file is out of date.

#include <iostream>

#include "reach_trajopt/common/cli_options.h"
#include "reach_trajopt/testing/parameter_tables.h"

namespace {

/// The tool's options (--help prints them): none but --help.
const reach_trajopt::CliTool kTool(
    "parameter_table", "> docs/parameters.md",
    "Prints the parameter table of every config section (docs/parameters.md) from the config\n"
    "structs' field tables.",
    {});

}  // namespace

int main(int argc, char** argv) {
  return kTool.run(argc, argv, [](const reach_trajopt::CliArgs& args) {
    if (!args.positional().empty()) {
      std::cerr << kTool.usageLine() << "\n";
      return 2;
    }
    std::cout << reach_trajopt::parameterTableMarkdown(reach_trajopt::parameterTables());
    return 0;
  });
}
