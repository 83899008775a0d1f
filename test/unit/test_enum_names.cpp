// The name tables of the enums that appear at the edges (step records, WALK lines, messages):
// every value has one name, names are unique, and reading a name back gives the value; an
// unknown name is an error that lists the names.

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ocp/transition_result.h"
#include "reach_trajopt/step/step_verdict.h"

using namespace reach_trajopt;

namespace {

template <typename E>
void expectRoundTrip(const EnumNames<E>& names, std::initializer_list<E> values) {
  std::set<std::string> seen;
  for (E v : values) {
    const std::string name = nameOf(names, v);
    EXPECT_NE(name, "?") << static_cast<int>(v);
    EXPECT_TRUE(seen.insert(name).second) << "duplicate name " << name;
    EXPECT_EQ(valueOf(names, name, "test"), v) << name;
  }
  EXPECT_EQ(names.size(), values.size());
}

}  // namespace

TEST(EnumNames, EveryStepVerdictHasOneNameThatReadsBack) {
  expectRoundTrip(stepVerdictNames(),
                  {StepVerdict::kNotChecked, StepVerdict::kKinematicallyFeasible,
                   StepVerdict::kKinematicallyInfeasible, StepVerdict::kReachable,
                   StepVerdict::kUnreachable, StepVerdict::kCheckError});
  EXPECT_STREQ(stepVerdictName(StepVerdict::kCheckError), "check_error");
}

TEST(EnumNames, EveryCertificateAndOcpStatusHasOneNameThatReadsBack) {
  expectRoundTrip(certificateNames(),
                  {Certificate::kNone, Certificate::kBridge, Certificate::kLocalSolve});
  expectRoundTrip(ocpStatusNames(),
                  {OcpStatus::kConverged, OcpStatus::kRelaxed, OcpStatus::kFailed});
  EXPECT_STREQ(certificateName(Certificate::kNone), "");  // the step records' empty column
}

TEST(EnumNames, AnUnknownNameIsAnErrorListingTheNames) {
  try {
    valueOf(stepVerdictNames(), "maybe", "plan_footstep response: verdict");
    FAIL() << "no error";
  } catch (const RequestError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("plan_footstep response: verdict 'maybe'"), std::string::npos) << what;
    EXPECT_NE(what.find("reachable|unreachable"), std::string::npos) << what;
  }
}
