#pragma once
/// \file parameter_tables.h
/// The field tables (common/config_fields.h) of every config section the shipped files hold
/// (config/biped.yaml, then config/sim.yaml), in file order: the source of docs/parameters.md
/// (`parameter_table > docs/parameters.md`) and of test_parameter_table, which checks that the
/// file is up to date and that every struct default equals the shipped value. In test/support/
/// (built, never installed): it sees every component's config. A struct given a table
/// (ConfigFields) is added to this list with one line.

#include <vector>

#include "reach_trajopt/common/config_fields.h"

namespace reach_trajopt {

/// Every ported config struct's table, in the order of the shipped files' sections.
std::vector<ParameterTable> parameterTables();

}  // namespace reach_trajopt
