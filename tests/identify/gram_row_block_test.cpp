// The Gram kernel of identify and diagnose against Eigen's rankUpdate: the same bits, entry by
// entry, over the shapes Eigen blocks differently (row blocks, depth blocks, the one-packet rows
// it sums as even and odd halves) and values over many magnitudes.
#include "offline/fit/gram_row_block.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace tpf::test {
namespace {

// Seeded rows over many magnitudes (products that round differently in another order).
Eigen::MatrixXd random_rows(Eigen::Index depth, Eigen::Index size, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd rows(depth, size);
  for (Eigen::Index k = 0; k < depth; ++k)
    for (Eigen::Index i = 0; i < size; ++i)
      rows(k, i) = normal(rng) * std::exp(3.0 * normal(rng));
  return rows;
}

// Lower-triangle entries where the two differ in any bit.
int differing_bits(const Eigen::MatrixXd& expected, const Eigen::MatrixXd& got) {
  int differing = 0;
  for (Eigen::Index j = 0; j < expected.cols(); ++j)
    for (Eigen::Index i = j; i < expected.rows(); ++i)
      differing += std::memcmp(&expected(i, j), &got(i, j), sizeof(double)) != 0;
  return differing;
}

TEST(GramRowBlock, EqualsEigensRankUpdateBitForBit) {
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (Eigen::Index size : {1, 2, 3, 5, 8, 13, 16, 27, 30, 33, 46, 50, 61, 70, 75}) {
    for (Eigen::Index depth : {1, 7, 8, 9, 23, 256, 300, 530}) {
      SCOPED_TRACE(testing::Message() << "size " << size << ", depth " << depth);
      const Eigen::MatrixXd rows = random_rows(depth, size, rng);
      Eigen::MatrixXd before = Eigen::MatrixXd::Zero(size, size);
      for (Eigen::Index j = 0; j < size; ++j)
        for (Eigen::Index i = 0; i < size; ++i)
          before(i, j) = normal(rng);  // a Gram already holding earlier blocks (and an upper part)
      Eigen::MatrixXd expected = before;
      expected.selfadjointView<Eigen::Lower>().rankUpdate(rows.transpose());
      offline::GramRowBlock block(size, depth);
      for (Eigen::Index k = 0; k < depth; ++k) {
        const Eigen::RowVectorXd row = rows.row(k);
        block.append(row.data());
      }
      EXPECT_TRUE(block.full());
      Eigen::MatrixXd got = before;
      block.add_to_lower(got);
      EXPECT_EQ(block.rows(), 0);
      EXPECT_EQ(differing_bits(expected, got), 0);
      EXPECT_TRUE(got.triangularView<Eigen::StrictlyUpper>().toDenseMatrix() ==
                  before.triangularView<Eigen::StrictlyUpper>().toDenseMatrix());
      // Not a vacuous comparison: the Gram moved by the rows.
      EXPECT_GT((got - before).norm(), 0.0);
    }
  }
}

TEST(GramRowBlock, EmptyBlockChangesNothing) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Identity(4, 4);
  offline::GramRowBlock(4, 8).add_to_lower(G);
  EXPECT_TRUE(G == Eigen::MatrixXd::Identity(4, 4));
}

// The augmented design row [φ, y, 1] and a reused block: the Gram of each block of rows alone.
TEST(GramRowBlock, AugmentedRowsOfReusedBlock) {
  std::mt19937_64 rng(29);
  offline::GramRowBlock block(11, 40);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(11, 11), got = expected;
  for (int round = 0; round < 3; ++round) {
    const Eigen::Index depth = 40 - 13 * round;
    Eigen::MatrixXd rows = random_rows(depth, 11, rng);
    rows.col(10).setOnes();
    for (Eigen::Index k = 0; k < depth; ++k) {
      const Eigen::RowVectorXd row = rows.row(k);
      block.append_augmented(row.data(), row[9]);
    }
    expected.selfadjointView<Eigen::Lower>().rankUpdate(rows.transpose());
    block.add_to_lower(got);
    EXPECT_EQ(differing_bits(expected, got), 0) << "round " << round;
  }
}

}  // namespace
}  // namespace tpf::test
