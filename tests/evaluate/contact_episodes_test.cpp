// Contact episodes from per-cycle contact flags: runs, skipped cycles, merging, peaks and joints.
#include "offline/replay/contact_episodes.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// 10 cycles at 0.1 s; two joints.
struct Flags {
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(10, 0.0, 0.9);
  Eigen::VectorXd contact = Eigen::VectorXd::Zero(10);
  Eigen::MatrixXd torque = Eigen::MatrixXd::Zero(10, 2);
  Eigen::VectorXd threshold = Eigen::Vector2d(0.5, 0.5);
};

TEST(ContactEpisodes, RunsStartAtTheFirstCycleInContactAndEndAtTheFirstOut) {
  Flags f;
  f.contact.segment(2, 3).setOnes();  // rows 2..4
  f.contact.segment(7, 3).setOnes();  // rows 7..9: the log ends in contact
  f.torque(3, 0) = -2.0;
  f.torque(4, 1) = 0.4;  // under its threshold: not one of the episode's joints
  f.torque(5, 0) = 9.0;  // out of contact: not in any peak
  f.torque(8, 1) = 1.5;
  const auto e = contact_episodes(f.t, f.contact, f.torque, f.threshold);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_DOUBLE_EQ(e[0].start_s, f.t[2]);
  EXPECT_DOUBLE_EQ(e[0].end_s, f.t[5]);
  EXPECT_DOUBLE_EQ(e[0].peak_abs_torque[0], 2.0);
  EXPECT_DOUBLE_EQ(e[0].peak_abs_torque[1], 0.4);
  EXPECT_EQ(e[0].joints, std::vector<int>{0});
  EXPECT_DOUBLE_EQ(e[1].start_s, f.t[7]);
  EXPECT_DOUBLE_EQ(e[1].end_s, f.t[9]);
  EXPECT_EQ(e[1].joints, std::vector<int>{1});
}

TEST(ContactEpisodes, ASkippedCycleContinuesTheStateBeforeIt) {
  Flags f;
  f.contact.segment(2, 5).setOnes();
  f.contact[4] = std::nan("");  // no answer inside the contact: still one episode
  f.contact[8] = std::nan("");  // no answer out of contact: no episode
  f.torque(4, 0) = std::nan("");
  const auto e = contact_episodes(f.t, f.contact, f.torque, f.threshold);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_DOUBLE_EQ(e[0].start_s, f.t[2]);
  EXPECT_DOUBLE_EQ(e[0].end_s, f.t[7]);
  EXPECT_DOUBLE_EQ(e[0].peak_abs_torque[0], 0.0);
  EXPECT_TRUE(e[0].joints.empty());
}

TEST(ContactEpisodes, EpisodesCloserThanTheMergeGapAreOne) {
  Flags f;
  f.contact.segment(1, 2).setOnes();  // rows 1..2, out at 0.3 s
  f.contact.segment(5, 2).setOnes();  // rows 5..6: 0.2 s after
  f.torque(6, 1) = 3.0;
  EXPECT_EQ(contact_episodes(f.t, f.contact, f.torque, f.threshold, 0.15).size(), 2u);
  const auto e = contact_episodes(f.t, f.contact, f.torque, f.threshold, 0.25);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_DOUBLE_EQ(e[0].start_s, f.t[1]);
  EXPECT_DOUBLE_EQ(e[0].end_s, f.t[7]);
  EXPECT_DOUBLE_EQ(e[0].peak_abs_torque[1], 3.0);
}

TEST(ContactEpisodes, NoContactNoEpisodeAndSizesAreChecked) {
  Flags f;
  EXPECT_TRUE(contact_episodes(f.t, f.contact, f.torque, f.threshold).empty());
  EXPECT_THROW(contact_episodes(f.t, f.contact.head(5), f.torque, f.threshold), Error);
  EXPECT_THROW(contact_episodes(f.t, f.contact, f.torque, Eigen::VectorXd::Ones(3)), Error);
}

}  // namespace
}  // namespace tpf::offline
