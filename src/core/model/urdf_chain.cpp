// Extracts the serial chain of revolute joints from a URDF, with urdfdom.
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

#include "tpf/common/error.hpp"
#include "tpf/model/robot_description.hpp"

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

Inertia<double> link_inertia(const urdf::Link& link, const std::string& file) {
  Inertia<double> in;
  if (!link.inertial) return in;
  const urdf::Inertial& u = *link.inertial;
  if (!(u.mass >= 0.0)) throw Error::at(file, 0, "link '" + link.name + "'", "mass must be >= 0");
  const Transform<double> origin = to_transform(u.origin);
  Matrix3<double> I;
  I << u.ixx, u.ixy, u.ixz, u.ixy, u.iyy, u.iyz, u.ixz, u.iyz, u.izz;
  const double smallest =
      Eigen::SelfAdjointEigenSolver<Matrix3<double>>(I).eigenvalues().minCoeff();
  if (!(smallest >= -1e-12))
    throw Error::at(file, 0, "link '" + link.name + "'", "inertia is not positive semi-definite");
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

/// Folds a subtree made only of fixed joints into `body` (expressed in the frame `pose` of `body`).
void fold_fixed_subtree(const urdf::Link& link, const Transform<double>& pose,
                        Inertia<double>& body, const std::string& file) {
  body = combine(body, link_inertia(link, file), pose);
  for (const auto& j : link.child_joints) {
    const auto child = std::find_if(link.child_links.begin(), link.child_links.end(),
                                    [&](const auto& l) { return l->name == j->child_link_name; });
    fold_fixed_subtree(**child, pose * to_transform(j->parent_to_joint_origin_transform), body,
                       file);
  }
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

}  // namespace

ChainDescription load_urdf_chain(const std::filesystem::path& urdf_file) {
  const std::string file = urdf_file.string();
  std::ifstream in(urdf_file);
  if (!in) throw Error::at(file, 0, "", "cannot open the URDF file");
  std::stringstream text;
  text << in.rdbuf();

  CapturingHandler handler;
  console_bridge::useOutputHandler(&handler);
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDF(text.str());
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

  ChainDescription chain;
  chain.source = file;
  chain.robot_name = urdf->getName();
  const urdf::Link* link = urdf->getRoot().get();
  chain.base_link = link->name;
  chain.inertias.push_back(Inertia<double>{});
  Inertia<double>* body = &chain.inertias.back();
  *body = link_inertia(*link, file);
  Transform<double> offset;  // fixed joints since the last moving link

  while (link != nullptr) {
    const urdf::Link* next = nullptr;
    const urdf::Joint* next_joint = nullptr;
    for (const auto& j : link->child_joints) {
      const auto child = std::find_if(link->child_links.begin(), link->child_links.end(),
                                      [&](const auto& l) { return l->name == j->child_link_name; });
      const urdf::Link& c = **child;
      const bool moving = j->type != urdf::Joint::FIXED || subtree_moves(c);
      if (!moving) {
        fold_fixed_subtree(c, offset * to_transform(j->parent_to_joint_origin_transform), *body,
                           file);
        continue;
      }
      if (next != nullptr) {
        throw Error::at(file, 0, "link '" + link->name + "'",
                        "the robot branches here (joints '" + next_joint->name + "' and '" +
                            j->name + "' both lead to moving joints); tpf needs a serial chain");
      }
      next = &c;
      next_joint = j.get();
    }
    if (next == nullptr) break;

    const urdf::Joint& j = *next_joint;
    const Transform<double> placement = offset * to_transform(j.parent_to_joint_origin_transform);
    if (j.type == urdf::Joint::FIXED) {
      offset = placement;  // a fixed joint between moving links: its child's mass joins `body`
      *body = combine(*body, link_inertia(*next, file), offset);
      link = next;
      continue;
    }
    if (j.type != urdf::Joint::REVOLUTE && j.type != urdf::Joint::CONTINUOUS) {
      static const char* names[] = {"unknown",  "revolute", "continuous", "prismatic",
                                    "floating", "planar",   "fixed"};
      throw Error::at(file, 0, "joint '" + j.name + "'",
                      std::string("is ") + names[j.type] +
                          "; tpf supports revolute and continuous joints only");
    }
    ChainJoint cj;
    cj.name = j.name;
    cj.child_link = next->name;
    cj.placement = placement;
    cj.axis = {j.axis.x, j.axis.y, j.axis.z};
    if (cj.axis.norm() < 1e-9) throw Error::at(file, 0, "joint '" + j.name + "'", "axis is zero");
    cj.axis.normalize();
    // A revolute joint whose <limit> gives neither lower nor upper (urdfdom reads both as 0, as in
    // Kinova's description) turns without end stops, like a continuous one.
    if (j.type == urdf::Joint::CONTINUOUS || !j.limits ||
        (j.limits->lower == 0.0 && j.limits->upper == 0.0)) {
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
    chain.joints.push_back(cj);
    chain.inertias.push_back(link_inertia(*next, file));
    body = &chain.inertias.back();
    offset = Transform<double>{};
    link = next;
  }
  if (chain.joints.empty()) throw Error::at(file, 0, "", "the URDF has no revolute joint");
  return chain;
}

}  // namespace tpf
