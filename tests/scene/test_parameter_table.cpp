// The parameter table: ranges are enforced, and the documentation is generated from it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/error.hpp"
#include "scene/parameter_table.hpp"

using namespace progsim;

TEST(ParameterTable, EnforcesOpenClosedAndIntegerRanges) {
  const ParameterSpec& nu = find_parameter("material", "poisson_ratio");
  EXPECT_NO_THROW(check_parameter(nu, 0.0));
  EXPECT_NO_THROW(check_parameter(nu, 0.499));
  EXPECT_THROW(check_parameter(nu, 0.5), Error);
  EXPECT_THROW(check_parameter(nu, -1.0), Error);
  EXPECT_THROW(check_parameter(nu, std::nan("")), Error);
  const ParameterSpec& iters = find_parameter("solver", "max_newton_iterations");
  EXPECT_NO_THROW(check_parameter(iters, 1));
  EXPECT_THROW(check_parameter(iters, 0), Error);
  EXPECT_THROW(check_parameter(iters, 1.5), Error);
  EXPECT_THROW(find_parameter("material", "stiffness"), Error);
}

TEST(ParameterTable, EveryDefaultIsInsideItsOwnRange) {
  for (const ParameterSpec& spec : parameter_table())
    EXPECT_NO_THROW(check_parameter(spec, spec.default_value)) << spec.group << "." << spec.name;
}

TEST(ParameterTable, SceneDocumentationShowsTheGeneratedTable) {
  std::ifstream in(std::string(PROGSIM_SOURCE_DIR) + "/scenes/README.md");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find(parameter_table_markdown()), std::string::npos)
      << "scenes/README.md is out of date; paste the output of `progsim params`";
}
