// TemporalSchedule (SPEC section 6): which frames are real, fixed and auto intervals. No GL.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "methods/neural/temporal/temporal_schedule.hpp"
#include "starnt/error.hpp"

using starnt::MethodOptions;
using starnt::TemporalSchedule;

namespace {

MethodOptions fixedInterval(int k) {
    MethodOptions o;
    o.neural.temporalInterval = k;
    return o;
}

MethodOptions autoInterval(double targetFps = 60.0) {
    MethodOptions o;
    o.neural.temporalAuto = true;
    o.neural.targetFps = targetFps;
    return o;
}

// "R" for a real frame, "i" for an interpolated one.
std::string pattern(TemporalSchedule& s, int frames) {
    std::string out;
    for (int i = 0; i < frames; ++i) out += s.nextFrameIsReal() ? 'R' : 'i';
    return out;
}

}  // namespace

TEST(TemporalSchedule, FixedIntervalPatternIsExact) {
    TemporalSchedule one(fixedInterval(1));
    EXPECT_EQ(pattern(one, 5), "RRRRR");
    TemporalSchedule two(fixedInterval(2));
    EXPECT_EQ(pattern(two, 7), "RiRiRiR");
    TemporalSchedule three(fixedInterval(3));
    EXPECT_EQ(pattern(three, 8), "RiiRiiRi");
    TemporalSchedule four(fixedInterval(4));
    EXPECT_EQ(pattern(four, 9), "RiiiRiiiR");
    EXPECT_EQ(four.groupInterval(), 4);
    TemporalSchedule eight(fixedInterval(starnt::kMaxTemporalInterval));  // beyond SPEC 6's 4
    EXPECT_EQ(pattern(eight, 17), "RiiiiiiiRiiiiiiiR");
    EXPECT_EQ(eight.groupInterval(), 8);
}

// lastOfGroup: the frame just scheduled is followed by a real one ("L" where it says so).
TEST(TemporalSchedule, LastOfGroupPrecedesEveryRealFrame) {
    for (int k : {1, 2, 3, 8}) {
        TemporalSchedule s(fixedInterval(k));
        std::string frames, last;
        for (int i = 0; i < 2 * k + 1; ++i) {
            frames += s.nextFrameIsReal() ? 'R' : 'i';
            last += s.lastOfGroup() ? 'L' : '.';
        }
        // Every frame before an R is the last of its group, and no other one is.
        for (size_t i = 0; i + 1 < frames.size(); ++i) EXPECT_EQ(last[i] == 'L', frames[i + 1] == 'R') << k << ": " << frames << " " << last;
    }
}

TEST(TemporalSchedule, FixedIgnoresMeasurements) {
    TemporalSchedule s(fixedInterval(3));
    s.recordRealFrameMs(100.0);  // far below any target: auto would say 1
    EXPECT_EQ(s.interval(), 3);
    EXPECT_EQ(pattern(s, 4), "RiiR");
}

TEST(TemporalSchedule, FirstFrameAfterResetIsReal) {
    TemporalSchedule s(fixedInterval(3));
    EXPECT_EQ(pattern(s, 2), "Ri");
    s.reset();
    EXPECT_EQ(s.groupInterval(), 0);
    EXPECT_EQ(pattern(s, 4), "RiiR");
}

TEST(TemporalSchedule, AutoIsPlainRenderingWithoutMeasurementOrBelowTarget) {
    TemporalSchedule s(autoInterval(60.0));
    EXPECT_EQ(s.interval(), 1);
    EXPECT_EQ(pattern(s, 3), "RRR");
    s.recordRealFrameMs(20.0);  // 50 fps < 60
    EXPECT_EQ(s.interval(), 1);
    s.recordRealFrameMs(17.0);  // mean 18.5 ms = 54 fps: still below
    EXPECT_EQ(s.interval(), 1);
    EXPECT_EQ(pattern(s, 3), "RRR");
}

TEST(TemporalSchedule, AutoIsFloorOfRateOverTargetUntilInterpolatedFramesAreMeasured) {
    struct Case {
        double ms, target;
        int want;
    };
    // 125/60 = 2.08, 200/60 = 3.33, 100/60 = 1.67, 100/30 = 3.33, 100/25 = 4, 62.5/30 = 2.08.
    // No interpolated frame is measured yet, so k is at least 2 (one must run to be measured).
    for (Case c : {Case{8.0, 60.0, 2}, Case{5.0, 60.0, 3}, Case{10.0, 60.0, 2}, Case{10.0, 30.0, 3},
                   Case{10.0, 25.0, 4}, Case{16.0, 30.0, 2}}) {
        TemporalSchedule s(autoInterval(c.target));
        s.recordRealFrameMs(c.ms);
        EXPECT_EQ(s.interval(), c.want) << c.ms << " ms at target " << c.target;
    }
}

TEST(TemporalSchedule, AutoFitsTheGroupInOneTargetFrameWithMeasuredInterpolatedCost) {
    struct Case {
        double real, interpolated;
        int want;
    };
    // T = 16.67 ms. k = 1 + floor((T - R) / I): 8.67/6 = 1.44, 8.67/3 = 2.89, 11.67/6 = 1.94,
    // 11.67/5.5 = 2.12, 6.67/6 = 1.11, 6.67/7 = 0.95, 8.67/0.5 = 17.3 (clamped to 4).
    for (Case c : {Case{8, 6, 2}, Case{8, 3, 3}, Case{5, 6, 2}, Case{5, 5.5, 3}, Case{10, 6, 2}, Case{10, 7, 1},
                   Case{8, 0.5, 4}, Case{8, 0.0, 4}}) {
        TemporalSchedule s(autoInterval(60.0));
        s.recordRealFrameMs(c.real);
        s.recordInterpolatedFrameMs(c.interpolated);
        EXPECT_EQ(s.interval(), c.want) << c.real << " ms real, " << c.interpolated << " ms interpolated";
    }
    // A cheap interpolated frame does not rescue a real frame below the target rate.
    TemporalSchedule slow(autoInterval(60.0));
    slow.recordRealFrameMs(20.0);
    slow.recordInterpolatedFrameMs(0.1);
    EXPECT_EQ(slow.interval(), 1);
}

TEST(TemporalSchedule, AutoCountsInterpolatedFramesAtRealCostUntilOneIsMeasured) {
    TemporalSchedule s(autoInterval(60.0));
    s.recordRealFrameMs(5.0);
    EXPECT_EQ(s.averageInterpolatedFrameMs(), 0.0);
    EXPECT_EQ(s.interval(), 3);  // floor(200 / 60), SPEC's rule
    s.recordInterpolatedFrameMs(6.0);  // a refresh frame costing more than the real one's share
    EXPECT_EQ(s.interval(), 2);
    for (int i = 0; i < 8; ++i) s.recordInterpolatedFrameMs(1.0);  // the window forgets the 6
    EXPECT_DOUBLE_EQ(s.averageInterpolatedFrameMs(), 1.0);
    EXPECT_EQ(s.interval(), 4);
    s.recordInterpolatedFrameMs(-1.0);  // ignored, as for real frames
    s.recordInterpolatedFrameMs(std::numeric_limits<double>::quiet_NaN());
    EXPECT_DOUBLE_EQ(s.averageInterpolatedFrameMs(), 1.0);
    s.reset();
    EXPECT_EQ(s.averageInterpolatedFrameMs(), 0.0);
    s.recordRealFrameMs(5.0);
    EXPECT_EQ(s.interval(), 3);
}

TEST(TemporalSchedule, AutoNeverExceedsFour) {
    for (double ms : {4.0, 1.0, 0.01, 1e-300, 0.0}) {
        TemporalSchedule s(autoInterval(60.0));
        s.recordRealFrameMs(ms);
        EXPECT_EQ(s.interval(), 4) << ms;
        EXPECT_EQ(pattern(s, 10), "RiiiRiiiRi") << ms;  // groups of 4, never 5
    }
}

TEST(TemporalSchedule, AutoIgnoresInvalidSamples) {
    TemporalSchedule s(autoInterval(60.0));
    s.recordRealFrameMs(-1.0);
    s.recordRealFrameMs(std::numeric_limits<double>::quiet_NaN());
    s.recordRealFrameMs(std::numeric_limits<double>::infinity());
    EXPECT_EQ(s.averageRealFrameMs(), 0.0);
    EXPECT_EQ(s.interval(), 1);
}

TEST(TemporalSchedule, AutoAveragesTheLastEightRealFrames) {
    TemporalSchedule s(autoInterval(60.0));
    for (int i = 0; i < 8; ++i) s.recordRealFrameMs(4.0);
    EXPECT_DOUBLE_EQ(s.averageRealFrameMs(), 4.0);
    EXPECT_EQ(s.interval(), 4);  // 250 fps
    s.recordRealFrameMs(20.0);   // evicts one 4: (7 * 4 + 20) / 8 = 6 ms
    EXPECT_DOUBLE_EQ(s.averageRealFrameMs(), 6.0);
    EXPECT_EQ(s.interval(), 2);  // 166.7 / 60 = 2.78
    for (int i = 0; i < 7; ++i) s.recordRealFrameMs(20.0);  // all eight are 20 now
    EXPECT_DOUBLE_EQ(s.averageRealFrameMs(), 20.0);
    EXPECT_EQ(s.interval(), 1);
}

TEST(TemporalSchedule, AutoIntervalChangesOnlyAtRealFrames) {
    TemporalSchedule s(autoInterval(60.0));
    EXPECT_TRUE(s.nextFrameIsReal());
    EXPECT_EQ(s.groupInterval(), 1);
    s.recordRealFrameMs(5.0);  // now 3, but the running group keeps 1
    EXPECT_EQ(s.interval(), 3);
    EXPECT_EQ(s.groupInterval(), 1);
    EXPECT_TRUE(s.nextFrameIsReal());  // new group latches 3
    EXPECT_EQ(s.groupInterval(), 3);
    s.recordRealFrameMs(45.0);         // mean 25 ms: 1 from the next group on
    EXPECT_EQ(s.interval(), 1);
    EXPECT_FALSE(s.nextFrameIsReal());  // the group of 3 runs to its end
    EXPECT_FALSE(s.nextFrameIsReal());
    EXPECT_EQ(s.groupInterval(), 3);
    EXPECT_TRUE(s.nextFrameIsReal());
    EXPECT_EQ(s.groupInterval(), 1);
    EXPECT_TRUE(s.nextFrameIsReal());
}

TEST(TemporalSchedule, ResetForgetsMeasurements) {
    TemporalSchedule s(autoInterval(60.0));
    s.recordRealFrameMs(2.0);
    EXPECT_EQ(s.interval(), 4);
    s.reset();
    EXPECT_EQ(s.interval(), 1);
    EXPECT_EQ(s.averageRealFrameMs(), 0.0);
}

TEST(TemporalSchedule, RejectsBadOptionsClearly) {
    for (int k : {0, starnt::kMaxTemporalInterval + 1, -1, 100}) {
        try {
            TemporalSchedule s(fixedInterval(k));
            ADD_FAILURE() << "interval " << k << " accepted";
        } catch (const starnt::Error& e) {
            EXPECT_NE(std::string(e.what()).find("1..8"), std::string::npos) << e.what();
        }
    }
    for (double fps : {0.0, -30.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        EXPECT_THROW(TemporalSchedule s(autoInterval(fps)), starnt::Error) << fps;
    }
    EXPECT_NO_THROW(TemporalSchedule s(fixedInterval(4)));
}
