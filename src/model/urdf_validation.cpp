/// \file urdf_validation.cpp
/// URDF checks before urdfdom and KDL (urdf_validation.h).

#include "reach_trajopt/model/urdf_validation.h"

#include <tinyxml2.h>

#include <Eigen/Eigenvalues>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {
namespace {

using tinyxml2::XMLElement;

std::string nameOf(const XMLElement* e) {
  const char* n = e->Attribute("name");
  return n ? n : "";
}

/// Throws unless attribute `attr` of `e` (when present, or always when `required`) is
/// `count` whitespace-separated finite numbers (count 0: any number of them).
void checkNumbers(const XMLElement* e, const char* attr, int count, bool required,
                  const std::string& owner) {
  const char* text = e->Attribute(attr);
  if (!text) {
    if (required) throw ModelError(owner + ": <" + e->Name() + "> has no attribute '" + attr + "'");
    return;
  }
  std::istringstream in(text);
  std::string token;
  int n = 0;
  while (in >> token) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
      throw ModelError(owner + ": <" + e->Name() + " " + attr + "=\"" + text + "\">: '" + token +
                       "' is not a finite number");
    ++n;
  }
  if (count > 0 && n != count) {
    std::ostringstream os;
    os << owner << ": <" << e->Name() << " " << attr << "=\"" << text << "\">: expected " << count
       << " numbers, got " << n;
    throw ModelError(os.str());
  }
}

void checkOrigin(const XMLElement* parent, const std::string& owner) {
  for (const XMLElement* o = parent->FirstChildElement("origin"); o;
       o = o->NextSiblingElement("origin")) {
    checkNumbers(o, "xyz", 3, false, owner);
    checkNumbers(o, "rpy", 3, false, owner);
  }
}

void checkLink(const XMLElement* link, const std::string& owner) {
  for (const char* child : {"visual", "collision"})
    for (const XMLElement* v = link->FirstChildElement(child); v; v = v->NextSiblingElement(child))
      checkOrigin(v, owner);
  const XMLElement* in = link->FirstChildElement("inertial");
  if (!in) return;
  checkOrigin(in, owner + " <inertial>");
  const XMLElement* mass = in->FirstChildElement("mass");
  if (!mass) throw ModelError(owner + ": <inertial> has no <mass>");
  checkNumbers(mass, "value", 1, true, owner);
  const XMLElement* inertia = in->FirstChildElement("inertia");
  if (!inertia) throw ModelError(owner + ": <inertial> has no <inertia>");
  for (const char* a : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"})
    checkNumbers(inertia, a, 1, true, owner);
}

void checkJoint(const XMLElement* joint, const std::string& owner) {
  checkOrigin(joint, owner);
  if (const XMLElement* axis = joint->FirstChildElement("axis"))
    checkNumbers(axis, "xyz", 3, false, owner);
  if (const XMLElement* limit = joint->FirstChildElement("limit"))
    for (const char* a : {"lower", "upper", "effort", "velocity"})
      checkNumbers(limit, a, 1, false, owner);
  if (const XMLElement* d = joint->FirstChildElement("dynamics"))
    for (const char* a : {"damping", "friction"}) checkNumbers(d, a, 1, false, owner);
  if (const XMLElement* c = joint->FirstChildElement("calibration"))
    for (const char* a : {"rising", "falling"}) checkNumbers(c, a, 1, false, owner);
  if (const XMLElement* s = joint->FirstChildElement("safety_controller"))
    for (const char* a : {"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"})
      checkNumbers(s, a, 1, false, owner);
}

std::string linkOwner(const std::string& name, const std::string& source) {
  return "link '" + name + "' of " + source;
}

/// Every <link>: named, once, within the count limit, valid inertia and shapes.
std::set<std::string> checkLinks(const XMLElement* robot, const std::string& source) {
  std::set<std::string> links;
  for (const XMLElement* l = robot->FirstChildElement("link"); l;
       l = l->NextSiblingElement("link")) {
    const std::string name = nameOf(l);
    if (name.empty()) throw ModelError("a <link> without a name in " + source);
    if (!links.insert(name).second)
      throw ModelError("link '" + name + "' is defined twice in " + source);
    if (static_cast<int>(links.size()) > kMaxUrdfLinks) {
      std::ostringstream os;
      os << source << " has more than " << kMaxUrdfLinks << " links (the limit)";
      throw ModelError(os.str());
    }
    checkLink(l, linkOwner(name, source));
  }
  if (links.empty()) throw ModelError("malformed URDF in " + source + ": no <link>");
  return links;
}

/// Every <joint>: named, once, valid numbers, known parent and child links, one parent per
/// link; fills child link -> parent link / joint.
void checkJoints(const XMLElement* robot, const std::string& source,
                 const std::set<std::string>& links, std::map<std::string, std::string>& parent_of,
                 std::map<std::string, std::string>& joint_of) {
  std::set<std::string> joints;
  for (const XMLElement* j = robot->FirstChildElement("joint"); j;
       j = j->NextSiblingElement("joint")) {
    const std::string name = nameOf(j);
    const std::string owner = "joint '" + name + "' of " + source;
    if (name.empty()) throw ModelError("a <joint> without a name in " + source);
    if (!joints.insert(name).second)
      throw ModelError("joint '" + name + "' is defined twice in " + source);
    checkJoint(j, owner);
    const XMLElement* p = j->FirstChildElement("parent");
    const XMLElement* c = j->FirstChildElement("child");
    const char* pl = p ? p->Attribute("link") : nullptr;
    const char* cl = c ? c->Attribute("link") : nullptr;
    if (!pl || !cl) throw ModelError(owner + ": needs <parent link=...> and <child link=...>");
    for (const char* l : {pl, cl})
      if (!links.count(l)) throw ModelError(owner + ": unknown link '" + std::string(l) + "'");
    if (std::string(pl) == cl)
      throw ModelError(owner + ": link '" + std::string(cl) + "' is its own parent (a loop)");
    const auto it = joint_of.find(cl);
    if (it != joint_of.end())
      throw ModelError("link '" + std::string(cl) + "' of " + source +
                       " is the child of two joints, '" + it->second + "' and '" + name +
                       "': the links must form a tree (closed loops are not supported)");
    joint_of[cl] = name;
    parent_of[cl] = pl;
  }
}

/// The links form one tree: no loop, one root.
void requireTree(const std::set<std::string>& links,
                 const std::map<std::string, std::string>& parent_of,
                 std::map<std::string, std::string>& joint_of, const std::string& source) {
  // Loops: walking up from any link must end at a root within |links| steps.
  std::set<std::string> reaches_root;
  for (const std::string& start : links) {
    std::vector<std::string> path;
    std::string l = start;
    std::set<std::string> on_path;
    while (!reaches_root.count(l)) {
      if (!on_path.insert(l).second)
        throw ModelError("the links of " + source + " form a loop through link '" + l +
                         "' (joint '" + joint_of[l] + "'): a URDF must be a tree");
      path.push_back(l);
      const auto p = parent_of.find(l);
      if (p == parent_of.end()) break;
      l = p->second;
    }
    reaches_root.insert(path.begin(), path.end());
  }
  std::vector<std::string> roots;
  for (const std::string& l : links)
    if (!parent_of.count(l)) roots.push_back(l);
  if (roots.size() != 1) {
    std::ostringstream os;
    os << source << " has " << roots.size() << " root links (";
    for (std::size_t i = 0; i < roots.size() && i < 5; ++i)
      os << (i ? ", " : "") << "'" << roots[i] << "'";
    os << (roots.size() > 5 ? ", ..." : "") << "): every link but one needs a parent joint";
    throw ModelError(os.str());
  }
}

}  // namespace

void validateUrdfXml(const std::string& xml, const std::string& source) {
  if (xml.size() > kMaxUrdfBytes) {
    std::ostringstream os;
    os << source << ": URDF of " << xml.size() << " bytes exceeds the limit of " << kMaxUrdfBytes
       << " bytes";
    throw ModelError(os.str());
  }
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
    throw ModelError("malformed URDF in " + source + ": " +
                     (doc.ErrorStr() ? doc.ErrorStr() : "XML error"));
  const XMLElement* robot = doc.FirstChildElement("robot");
  if (!robot) throw ModelError("malformed URDF in " + source + ": no <robot> element");

  const std::set<std::string> links = checkLinks(robot, source);
  std::map<std::string, std::string> parent_of, joint_of;  // child link -> parent link / joint
  checkJoints(robot, source, links, parent_of, joint_of);
  requireTree(links, parent_of, joint_of, source);
}

void validateUrdf(const urdf::ModelInterface& urdf, const std::string& source) {
  for (const auto& kv : urdf.joints_) {
    const urdf::Joint& j = *kv.second;
    if (j.type != urdf::Joint::REVOLUTE && j.type != urdf::Joint::CONTINUOUS &&
        j.type != urdf::Joint::PRISMATIC)
      continue;
    const Eigen::Vector3d a(j.axis.x, j.axis.y, j.axis.z);
    if (!a.allFinite() || a.norm() < 1e-9) {
      std::ostringstream os;
      os << "joint '" << j.name << "' of " << source << ": axis [" << a.transpose()
         << "] is zero or not finite (a revolute, continuous or prismatic joint needs a "
            "direction)";
      throw ModelError(os.str());
    }
  }
  for (const auto& kv : urdf.links_) {
    const urdf::Link& link = *kv.second;
    if (!link.inertial) continue;
    const urdf::Inertial& in = *link.inertial;
    const std::string owner = "link '" + link.name + "' of " + source;
    const double vals[] = {in.mass, in.ixx, in.ixy, in.ixz, in.iyy, in.iyz, in.izz};
    for (double v : vals)
      if (!std::isfinite(v)) throw ModelError("non-finite inertial value in " + owner);
    Eigen::Matrix3d I;
    I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    std::ostringstream os;
    if (in.mass < 0.0) {
      os << "negative mass " << in.mass << " kg in " << owner;
      throw ModelError(os.str());
    }
    if (in.mass == 0.0) {
      if (I.cwiseAbs().maxCoeff() > kInertiaAbsTolerance) {
        os << owner << ": mass 0 with a non-zero inertia (max entry " << I.cwiseAbs().maxCoeff()
           << " kg m^2): a massless link must have zero inertia";
        throw ModelError(os.str());
      }
      continue;
    }
    const Eigen::Vector3d lambda =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I, Eigen::EigenvaluesOnly)
            .eigenvalues();  // ascending
    const double largest = std::max(lambda(2), 0.0);
    if (lambda(0) < -(kInertiaAbsTolerance + kInertiaRelTolerance * largest)) {
      os << owner << ": inertia is not positive semidefinite (principal moments "
         << lambda.transpose() << " kg m^2)";
      throw ModelError(os.str());
    }
    // Principal second moments (sum - 2 lambda_k) / 2 = integral of x_k^2 dm >= 0.
    const double violation = std::max(0.0, lambda(2) - lambda(0) - lambda(1));
    if (violation > kInertiaTriangleAbsTolerance &&
        std::sqrt(violation / (2.0 * in.mass)) > kInertiaTriangleLength) {
      os << owner << ": inertia breaks the triangle inequality (principal moments "
         << lambda.transpose() << " kg m^2: " << lambda(0) << " + " << lambda(1) << " < "
         << lambda(2) << ")";
      throw ModelError(os.str());
    }
  }
}

}  // namespace reach_trajopt
