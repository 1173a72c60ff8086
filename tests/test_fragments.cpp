#include <gtest/gtest.h>

#include "starnt/tools/fragments.hpp"

using namespace starnt;

TEST(Fragments, OverOfTwoLayersMatchesHandComputation) {
    FragmentList f = {{{1, 0, 0}, 0.5f, 0.7f, 1}, {{0, 0, 1}, 0.25f, 0.2f, 0}};
    sortByDepth(f);
    ASSERT_FLOAT_EQ(f[0].depth, 0.2f);
    glm::vec3 c = compositeOver(f, glm::vec3(1.0f));
    // blue 0.25 in front, then red 0.5 (through 0.75), then white background through 0.375.
    EXPECT_NEAR(c.r, 0.75f * 0.5f + 0.375f, 1e-6);
    EXPECT_NEAR(c.g, 0.375f, 1e-6);
    EXPECT_NEAR(c.b, 0.25f + 0.375f, 1e-6);
    EXPECT_NEAR(totalTransmittance(f), 0.375f, 1e-6);
}

TEST(Fragments, SubmissionSortUsesOrderKey) {
    FragmentList f = {{{1, 0, 0}, 0.5f, 0.1f, 7}, {{0, 1, 0}, 0.5f, 0.9f, 3}};
    sortBySubmission(f);
    EXPECT_EQ(f[0].order, 3u);
}
