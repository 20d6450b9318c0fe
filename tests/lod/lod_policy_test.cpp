#include "lod/lod_policy.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/diagnostic_renderer.h"

namespace spire::lod {
namespace {

struct Parsed {
  std::optional<LodPolicy> policy;
  std::string diagnostics;
};

Parsed parse(std::string text) {
  SourceManager sources;
  DiagnosticList diags;
  Parsed parsed;
  parsed.policy = parseLodPolicy("policy.json", std::move(text), sources, diags);
  parsed.diagnostics = renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  return parsed;
}

TEST(LodPolicyTest, ReadsLevelsNearestFirst) {
  const Parsed p = parse(R"({"levels": [{"member": "LodHQ", "until": 12}, {"member": "LodMQ", "until": 40},
                                        {"member": "LodLQ"}], "hysteresis": 0.2, "transitionFrames": 4})");
  ASSERT_TRUE(p.policy) << p.diagnostics;
  ASSERT_EQ(p.policy->levels.size(), 3U);
  EXPECT_EQ(p.policy->levels[1].member, "LodMQ");
  EXPECT_FLOAT_EQ(p.policy->levels[1].until, 40.0F);
  EXPECT_TRUE(std::isinf(p.policy->levels[2].until));
  EXPECT_FLOAT_EQ(p.policy->hysteresis, 0.2F);
  EXPECT_EQ(p.policy->transitionFrames, 4U);
}

TEST(LodPolicyTest, FormattedPolicyReadsBackTheSame) {
  const Parsed p = parse(R"({"levels": [{"member": "A", "until": 7.5}, {"member": "B"}]})");
  ASSERT_TRUE(p.policy) << p.diagnostics;
  const Parsed again = parse(formatLodPolicy(*p.policy));
  ASSERT_TRUE(again.policy) << again.diagnostics;
  EXPECT_EQ(formatLodPolicy(*again.policy), formatLodPolicy(*p.policy));
  EXPECT_FLOAT_EQ(again.policy->levels[0].until, 7.5F);
}

TEST(LodPolicyTest, BadPoliciesAreReportedAtTheirValues) {
  struct Case {
    const char* text;
    const char* message;
  };
  const Case cases[] = {
      {R"({"levels": [{"member": "A", "until": 20}, {"member": "B", "until": 10}, {"member": "C"}]})",
       "policy.json:1:43: error[E7004]: level 1 ends at 10, not beyond level 0 (20)"},
      {R"({"levels": [{"member": "A"}, {"member": "B"}]})", "a level before the last has no 'until'"},
      {R"({"levels": [{"member": "A", "until": 3}]})", "the last level has no 'until'"},
      {R"({"levels": [{"until": 3}, {"member": "B"}]})", "a level has no 'member'"},
      {R"({"levels": [{"member": "A"}], "hysterisis": 0.1})", "did you mean 'hysteresis'?"},
      {R"({"levels": [{"member": "A"}], "hysteresis": 1.5})", "'hysteresis'"},
      {R"({"levels": []})", "'levels'"},
      {R"({"hysteresis": 0.1})", "the policy has no 'levels'"},
      {R"({"levels": [{"member": "A"}],})", "E7001"},
  };
  for (const Case& c : cases) {
    const Parsed p = parse(c.text);
    EXPECT_FALSE(p.policy) << c.text;
    EXPECT_NE(p.diagnostics.find(c.message), std::string::npos) << c.text << "\n" << p.diagnostics;
  }
}

}  // namespace
}  // namespace spire::lod
