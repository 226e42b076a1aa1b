// The same arm as a KDL chain, for peer comparisons in tests and benchmarks.
#pragma once

#include <kdl/chain.hpp>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <stdexcept>
#include <string>

namespace tpf::test {

/// The chain from `base` to `tip` of a URDF, as KDL parses it.
inline KDL::Chain kdl_chain(const std::string& urdf, const std::string& base,
                            const std::string& tip) {
  KDL::Tree tree;
  if (!kdl_parser::treeFromFile(urdf, tree)) throw std::runtime_error("KDL cannot parse " + urdf);
  KDL::Chain chain;
  if (!tree.getChain(base, tip, chain)) throw std::runtime_error("KDL: no chain in " + urdf);
  return chain;
}

}  // namespace tpf::test
