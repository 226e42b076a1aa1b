// Extracts a chain of revolute and prismatic joints from a URDF, with urdfdom: the serial robot,
// or the path between two named links of a tree with the other branches folded in as fixed mass.
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <fstream>
#include <iostream>
#include <limits>
#include <mutex>
#include <set>
#include <sstream>
#include <vector>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"
#include "tpf/model/robot_description.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf {
namespace {

/// Captures urdfdom's error messages so that ours can quote them instead of printing to stderr.
class CapturingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
      messages += (messages.empty() ? "" : "; ") + text;
  }
  std::string messages;
};

Transform<double> to_transform(const urdf::Pose& pose) {
  Transform<double> t;
  t.R = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
            .normalized()
            .toRotationMatrix();
  t.p = {pose.position.x, pose.position.y, pose.position.z};
  return t;
}

/// The 1-based line of the `<link>` element named `name` in `text`, 0 when not found.
long link_line(const std::string& text, const std::string& name) {
  for (std::size_t at = text.find("<link"); at != std::string::npos;
       at = text.find("<link", at + 1)) {
    const std::string tag = text.substr(at, text.find('>', at) - at);
    if (tag.find("name=\"" + name + "\"") != std::string::npos ||
        tag.find("name='" + name + "'") != std::string::npos)
      return 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
  }
  return 0;
}

/// Where a link sits, for messages: the file, its text (for line numbers) and the link.
struct LinkSite {
  const std::string& file;
  const std::string& text;
  const urdf::Link& link;
  Error error(const std::string& message) const {
    return Error::at(file, link_line(text, link.name), "link '" + link.name + "'", message);
  }
};

std::string format_moment(double value) {
  std::ostringstream s;
  s.precision(9);
  s << value;
  return s.str();
}

/// The triangle inequality every rigid body's inertia meets (each moment at most the sum of the
/// other two), checked with a relative tolerance for the rounding of CAD exports. Returns the
/// broken inequality ("ixx + iyy = 0.002 < izz = 0.003"), naming the file's diagonal entries
/// when one of their inequalities fails (each frame's diagonal must meet it too), else the
/// principal moments; empty when the tensor is physical.
std::string broken_triangle_inequality(const Matrix3<double>& I) {
  constexpr double kRelativeTolerance = 1e-9;
  const Vector3<double> m = Eigen::SelfAdjointEigenSolver<Matrix3<double>>(I).eigenvalues();
  const double tolerance = kRelativeTolerance * std::abs(I.trace());
  if (m[0] + m[1] - m[2] >= -tolerance) return {};  // ascending: the one binding inequality
  static constexpr std::array<const char*, 3> kName = {"ixx", "iyy", "izz"};
  static constexpr std::array<std::array<int, 3>, 3> kTriples = {{{0, 1, 2}, {0, 2, 1}, {1, 2, 0}}};
  for (const auto& [a, b, c] : kTriples) {  // I_aa + I_bb >= I_cc
    const double sum = I(a, a) + I(b, b);
    if (sum - I(c, c) < -tolerance)
      return std::string(kName[a]) + " + " + kName[b] + " = " + format_moment(sum) + " < " +
             kName[c] + " = " + format_moment(I(c, c));
  }
  return "principal moments I1 + I2 = " + format_moment(m[0] + m[1]) +
         " < I3 = " + format_moment(m[2]);
}

/// Prints `message` to stderr as a warning, once per process; after kMaxWarnings different
/// ones (a fuzzer, a batch over many files), no more.
void warn_once(const std::string& message) {
  constexpr std::size_t kMaxWarnings = 100;
  static std::mutex mutex;
  static std::set<std::string> warned;
  const std::lock_guard<std::mutex> lock(mutex);
  if (warned.size() > kMaxWarnings || !warned.insert(message).second) return;
  std::cerr << "tpf: warning: "
            << (warned.size() > kMaxWarnings ? "more URDF warnings, not shown" : message) << "\n";
}

/// The link's inertia in its frame. `moves`: a joint moves it. The base (the root and the links
/// fixed to it) never enters the dynamics, so its tensor is not checked for being physical.
Inertia<double> link_inertia(const LinkSite& site, bool moves) {
  Inertia<double> in;
  const urdf::Link& link = site.link;
  if (!link.inertial) return in;
  const urdf::Inertial& u = *link.inertial;
  if (!(u.mass >= 0.0)) throw site.error("mass must be >= 0");
  const Transform<double> origin = to_transform(u.origin);
  Matrix3<double> I;
  I << u.ixx, u.ixy, u.ixz, u.ixy, u.iyy, u.iyz, u.ixz, u.iyz, u.izz;
  const double smallest =
      Eigen::SelfAdjointEigenSolver<Matrix3<double>>(I).eigenvalues().minCoeff();
  if (!(smallest >= -1e-12)) throw site.error("inertia is not positive semi-definite");
  // Not physical, yet M(q) stays positive definite and every algorithm computes: a warning, as
  // makers publish such tensors (Kinova's Gen3 description, data/real/kinova-gen3).
  if (const std::string broken = moves ? broken_triangle_inequality(I) : std::string();
      !broken.empty())
    warn_once(site.error("inertia breaks the triangle inequality (" + broken +
                         " kg·m²): no rigid body has this inertia; check the "
                         "<inertia> values and their frame")
                  .what());
  in.mass = u.mass;
  in.com = origin.p;
  in.rotational = origin.R * I * origin.R.transpose();
  return in;
}

/// Adds body b, whose frame sits at `pose` in a's frame, to body a (same frame as a).
Inertia<double> combine(const Inertia<double>& a, const Inertia<double>& b,
                        const Transform<double>& pose) {
  const double m = a.mass + b.mass;
  if (m <= 0.0) return a;
  const Vector3<double> cb = pose.apply(b.com);
  Inertia<double> out;
  out.mass = m;
  out.com = (a.mass * a.com + b.mass * cb) / m;
  auto shift = [&](const Matrix3<double>& Ic, double mass,
                   const Vector3<double>& c) -> Matrix3<double> {
    const Vector3<double> d = c - out.com;
    return Ic + mass * (d.squaredNorm() * Matrix3<double>::Identity() - d * d.transpose());
  };
  out.rotational = shift(a.rotational, a.mass, a.com) +
                   shift(pose.R * b.rotational * pose.R.transpose(), b.mass, cb);
  return out;
}

bool subtree_moves(const urdf::Link& link) {
  for (const auto& j : link.child_joints) {
    if (j->type != urdf::Joint::FIXED) return true;
  }
  for (const auto& c : link.child_links) {
    if (subtree_moves(*c)) return true;
  }
  return false;
}

/// Folds the subtree below `site.link` (included), whose frame sits at `pose` in `body`'s frame,
/// into `body`: fixed joints as they are, movable ones at their zero position (the joint frame at
/// its <origin>). Returns whether any of its links declares an <inertial>.
bool fold_subtree(const LinkSite& site, const Transform<double>& pose, bool moves,
                  Inertia<double>& body) {
  const urdf::Link& link = site.link;
  body = combine(body, link_inertia(site, moves), pose);
  bool declared = link.inertial != nullptr;
  for (const auto& j : link.child_joints) {
    const auto child = std::find_if(link.child_links.begin(), link.child_links.end(),
                                    [&](const auto& l) { return l->name == j->child_link_name; });
    declared |= fold_subtree({site.file, site.text, **child},
                             pose * to_transform(j->parent_to_joint_origin_transform), moves, body);
  }
  return declared;
}

/// The rigid body a joint moves, as the walk down the chain builds it: the joint's child link
/// and whether any link folded into the body declares an <inertial>.
struct MovingBody {
  const urdf::Link* link = nullptr;  ///< nullptr: the base, which may be massless
  std::string joint;
  bool declared = false;
};

/// Refuses a moving body none of whose links has an <inertial>: a link the file forgot, which
/// would move massless (an explicit <mass value="0"/> is a choice and passes). A massless frame
/// fixed to a link that has one (a tool or flange frame) is part of a body with mass and passes.
void require_declared_mass(const MovingBody& body, const std::string& file,
                           const std::string& text) {
  if (body.link == nullptr || body.declared) return;
  throw Error::at(file, link_line(text, body.link->name), "",
                  "link '" + body.link->name + "' has no <inertial>: it moves with joint '" +
                      body.joint +
                      "' and no link fixed to it has one, so it would move without mass; "
                      "give it an <inertial> (with <mass value=\"0\"/> if it has none)");
}

/// urdfdom links own their children (shared_ptr) and does not detect loops (ros/urdfdom#154): a
/// URDF with a loop leaves a reference cycle. Cutting every child list on exit frees any model.
struct CutChildLinksOnExit {
  const urdf::ModelInterface& model;
  ~CutChildLinksOnExit() {
    for (const auto& [name, link] : model.links_)
      link->child_links.clear();
  }
};

/// Refuses a link reached twice from the root, or never: a loop (or two paths to one link) is not
/// a tree, and walking it would never end.
void require_tree(const urdf::ModelInterface& model, const std::string& file) {
  std::set<const urdf::Link*> seen;
  std::vector<const urdf::Link*> open = {model.getRoot().get()};
  while (!open.empty()) {
    const urdf::Link* link = open.back();
    open.pop_back();
    if (!seen.insert(link).second)
      throw Error::at(file, 0, "link '" + link->name + "'",
                      "is reached twice from the root (the URDF has a loop); tpf needs a tree");
    for (const auto& child : link->child_links)
      open.push_back(child.get());
  }
  for (const auto& [name, link] : model.links_)
    if (!seen.contains(link.get()))
      throw Error::at(file, 0, "link '" + name + "'",
                      "is not connected to the root link '" + model.getRoot()->name +
                          "' (the URDF has a loop); tpf needs a tree");
}

/// A revolute, continuous or prismatic URDF joint as a chain joint, placed at `placement`.
ChainJoint chain_joint(const urdf::Joint& j, const urdf::Link& child,
                       const Transform<double>& placement, const std::string& file) {
  ChainJoint cj;
  cj.name = j.name;
  cj.child_link = child.name;
  cj.placement = placement;
  cj.type = j.type == urdf::Joint::PRISMATIC ? JointType::prismatic : JointType::revolute;
  cj.axis = {j.axis.x, j.axis.y, j.axis.z};
  if (cj.axis.norm() < 1e-9) throw Error::at(file, 0, "joint '" + j.name + "'", "axis is zero");
  cj.axis.normalize();
  const bool no_range = !j.limits || (j.limits->lower == 0.0 && j.limits->upper == 0.0);
  if (cj.type == JointType::prismatic && no_range) {
    throw Error::at(file, 0, "joint '" + j.name + "'",
                    "is prismatic without a travel range; give it <limit lower=\"...\" "
                    "upper=\"...\"> in m (and velocity in m/s, effort in N)");
  }
  // A revolute joint whose <limit> gives neither lower nor upper (urdfdom reads both as 0, as in
  // Kinova's description) turns without end stops, like a continuous one.
  if (j.type == urdf::Joint::CONTINUOUS || no_range) {
    cj.lower = -std::numeric_limits<double>::infinity();
    cj.upper = std::numeric_limits<double>::infinity();
  } else {
    cj.lower = j.limits->lower;
    cj.upper = j.limits->upper;
    if (!(cj.lower < cj.upper))
      throw Error::at(file, 0, "joint '" + j.name + "'",
                      "<limit> lower " + std::to_string(cj.lower) + " is not below upper " +
                          std::to_string(cj.upper));
  }
  if (j.limits) {
    cj.velocity_limit = j.limits->velocity;
    cj.effort_limit = j.limits->effort;
  }
  return cj;
}

/// The child link a joint of `link` leads to.
const urdf::Link& child_of(const urdf::Link& link, const urdf::Joint& j) {
  return **std::find_if(link.child_links.begin(), link.child_links.end(),
                        [&](const auto& l) { return l->name == j.child_link_name; });
}

/// Looks up a link the robot file names as an end of the chain.
const urdf::Link& named_link(const urdf::ModelInterface& model, const std::string& name,
                             const char* key, const ChainEnds& ends, const std::string& file) {
  const urdf::LinkConstSharedPtr link = model.getLink(name);
  if (!link)
    throw Error::at(file, 0, "",
                    "has no link '" + name + "' (" + key + " of " +
                        (ends.source.empty() ? std::string("the chain") : ends.source) +
                        "); name a link of this URDF");
  return *link;
}

/// The links from `root` to `tip` (both included), from the tip's parents up.
std::vector<const urdf::Link*> path_between(const urdf::Link& root, const urdf::Link& tip,
                                            const ChainEnds& ends, const std::string& file,
                                            const std::string& text) {
  std::vector<const urdf::Link*> path;
  for (const urdf::Link* link = &tip; link != nullptr; link = link->getParent().get()) {
    path.push_back(link);
    if (link == &root) {
      std::reverse(path.begin(), path.end());
      if (path.size() < 2)
        throw Error::at(file, link_line(text, tip.name), "link '" + tip.name + "'",
                        "is both root_link and tip_link" +
                            (ends.source.empty() ? std::string() : " in " + ends.source) +
                            "; the tip must lie below the root");
      return path;
    }
  }
  throw Error::at(file, link_line(text, tip.name), "link '" + tip.name + "'",
                  "(tip_link) does not lie below root_link '" + root.name + "'" +
                      (ends.source.empty() ? std::string() : " in " + ends.source) +
                      "; name a root link the tip hangs from (the path from the root to the tip "
                      "is the chain)");
}

/// The links from `root` down the one branch that moves, to where nothing moves any more: the
/// chain of a serial robot. Refuses a link with two children that lead to moving joints.
std::vector<const urdf::Link*> serial_path(const urdf::Link& root, const std::string& file,
                                           const std::string& text) {
  std::vector<const urdf::Link*> path = {&root};
  for (;;) {
    const urdf::Link& link = *path.back();
    const urdf::Joint* next = nullptr;
    for (const auto& j : link.child_joints) {
      if (j->type == urdf::Joint::FIXED && !subtree_moves(child_of(link, *j))) continue;
      if (next != nullptr) {
        throw Error::at(file, link_line(text, link.name), "link '" + link.name + "'",
                        "the robot branches here (joints '" + next->name + "' and '" + j->name +
                            "' both lead to moving joints); tpf needs a serial chain: name its "
                            "ends in the robot file (\"root_link\" and \"tip_link\") to cut the "
                            "chain from root to tip out of the tree, the other branches folded "
                            "in as fixed mass");
      }
      next = j.get();
    }
    if (next == nullptr) return path;
    path.push_back(&child_of(link, *next));
  }
}

}  // namespace

ChainDescription load_urdf_chain(const std::filesystem::path& urdf_file, const ChainEnds& ends) {
  const std::string file = urdf_file.string();
  std::ifstream in(urdf_file);
  if (!in) throw Error::at(file, 0, "", "cannot open the URDF file");
  std::stringstream text;
  text << in.rdbuf();
  const std::string content = text.str();

  CapturingHandler handler;
  console_bridge::useOutputHandler(&handler);
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDF(content);
  console_bridge::restorePreviousOutputHandler();
  if (!urdf) {
    throw Error::at(
        file, 0, "",
        "not a valid URDF" + (handler.messages.empty() ? "" : " (" + handler.messages + ")"));
  }
  const CutChildLinksOnExit cut{*urdf};
  // urdfdom logs some errors and goes on without the element (a mass of "heavy" or "nan" drops
  // the link's <inertial>: a massless link); any error refuses the file.
  if (!handler.messages.empty())
    throw Error::at(file, 0, "", "not a valid URDF (" + handler.messages + ")");
  require_tree(*urdf, file);

  const urdf::Link& root =
      ends.root.empty() ? *urdf->getRoot() : named_link(*urdf, ends.root, "root_link", ends, file);
  const std::vector<const urdf::Link*> path =
      ends.tip.empty() ? serial_path(root, file, content)
                       : path_between(root, named_link(*urdf, ends.tip, "tip_link", ends, file),
                                      ends, file, content);

  ChainDescription chain;
  chain.source = file;
  chain.robot_name = urdf->getName();
  chain.base_link = root.name;
  chain.tip_link = path.back()->name;
  chain.inertias.push_back(link_inertia({file, content, root}, false));
  Inertia<double>* body = &chain.inertias.back();
  MovingBody moving;         // the base first: no inertial required
  Transform<double> offset;  // fixed joints since the last moving link

  for (std::size_t i = 0; i < path.size(); ++i) {
    const urdf::Link& link = *path[i];
    const urdf::Link* next = i + 1 < path.size() ? path[i + 1] : nullptr;
    const urdf::Joint* next_joint = nullptr;
    // Every branch off the chain: fixed mass of the chain link it hangs from.
    for (const auto& j : link.child_joints) {
      const urdf::Link& c = child_of(link, *j);
      if (&c == next) {
        next_joint = j.get();
        continue;
      }
      moving.declared |= fold_subtree({file, content, c},
                                      offset * to_transform(j->parent_to_joint_origin_transform),
                                      moving.link != nullptr, *body);
    }
    if (next == nullptr) break;

    const urdf::Joint& j = *next_joint;
    const Transform<double> placement = offset * to_transform(j.parent_to_joint_origin_transform);
    if (j.type == urdf::Joint::FIXED) {
      offset = placement;  // a fixed joint between moving links: its child's mass joins `body`
      *body = combine(*body, link_inertia({file, content, *next}, moving.link != nullptr), offset);
      moving.declared |= next->inertial != nullptr;
      continue;
    }
    if (j.type != urdf::Joint::REVOLUTE && j.type != urdf::Joint::CONTINUOUS &&
        j.type != urdf::Joint::PRISMATIC) {
      static const char* names[] = {"unknown",  "revolute", "continuous", "prismatic",
                                    "floating", "planar",   "fixed"};
      throw Error::at(file, 0, "joint '" + j.name + "'",
                      std::string("is ") + names[j.type] +
                          "; tpf supports revolute, continuous and prismatic joints only (make "
                          "it fixed, or end the chain before it with \"tip_link\")");
    }
    require_declared_mass(moving, file, content);
    chain.joints.push_back(chain_joint(j, *next, placement, file));
    chain.inertias.push_back(link_inertia({file, content, *next}, true));
    body = &chain.inertias.back();
    moving = {next, j.name, next->inertial != nullptr};
    offset = Transform<double>{};
  }
  require_declared_mass(moving, file, content);
  if (chain.joints.empty())
    throw Error::at(file, 0, "",
                    "the chain from link '" + chain.base_link + "' to link '" + chain.tip_link +
                        "' has no revolute, continuous or prismatic joint");
  return chain;
}

}  // namespace tpf

TPF_UNOPTIMISED_WHEN_SANITIZED_END
