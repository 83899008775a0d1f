/// parameter_table: the parameter table of every config section (docs/parameters.md), from
/// the field tables of the config structs (include/reach_trajopt/common/config_fields.h).
///
///   parameter_table > docs/parameters.md    regenerate the file
///
/// Exit status: 0, or 2 on an error. test_parameter_table fails when the file is out of date.

#include <iostream>

#include "reach_trajopt/testing/parameter_tables.h"

int main(int argc, char** argv) {
  if (argc > 1) {
    std::cerr << "usage: " << argv[0] << " > docs/parameters.md\n";
    return 2;
  }
  try {
    std::cout << reach_trajopt::parameterTableMarkdown(reach_trajopt::parameterTables());
  } catch (const std::exception& e) {
    std::cerr << "parameter_table: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
