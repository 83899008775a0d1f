/// bench_dynamics: time of one rigid-body dynamics evaluation of eq. (1), ours against Pinocchio.
///
///   bench_dynamics <urdf> <pinocchio_model.txt> [--freeflyer-model FILE] [--rounds N]
///                  [--batch K] [--frames a,b] [--robot NAME]
///
/// <pinocchio_model.txt> is the same URDF loaded by Pinocchio's own parser (Python, the `pin`
/// wheel) with the composite root joint PX PY PZ RZ RY RX (= our floating base) and saved with
/// Model.saveToText: loading it here keeps the wheel's urdfdom/tinyxml2 out of this process,
/// which already holds Debian's (same symbol names, different versions).
///
/// Timed, per call, median over rounds; ours and Pinocchio interleaved in every round (which
/// goes first alternates), each round a batch of K calls (default 20) cycling over 64 random
/// states:
///   dynamics.full         ours: update + massMatrix + bias + 2 x (frameJacobian, frameJdotQd)
///                         ref:  crba (+ mirror to the lower triangle) + nonLinearEffects
///                               + computeJointJacobians + 2 getFrameJacobian
///                               + forwardKinematics(q, v, 0) + 2 getFrameClassicalAcceleration
///   dynamics.mass_matrix  ours: update + massMatrix        ref: crba (+ mirror)
///   dynamics.bias         ours: update + bias              ref: nonLinearEffects
/// (our queries need update() first, so it is part of our cost; Pinocchio's crba and
/// nonLinearEffects do their own forward pass.) Before timing, both are evaluated at one state
/// and the largest relative differences are printed, so the benchmark cannot time wrong work.
/// Output lines: BENCH <name> robot=NAME ours_us=... ref=pinocchio ref_us=... ratio=ours/ref
/// (NAME from --robot, default the URDF's file name without extension).
///
/// --freeflyer-model: the same URDF with Pinocchio's usual FreeFlyer root (quaternion, n_q + 1
/// positions), timed in the same rounds and printed as `info:` lines only. Pinocchio's composite
/// root evaluates six 1-dof joints where the FreeFlyer is one 6-dof joint, so this says how much
/// of the ratio comes from the coordinate choice rather than from the algorithms.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <pinocchio/algorithm/center-of-mass.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/frames.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/multibody.hpp>
#include <pinocchio/serialization.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "reach_trajopt/model/robot_model.h"

namespace rt = reach_trajopt;
namespace pin = pinocchio;

namespace {

constexpr int kStates = 64;

struct Options {
  std::string urdf;
  std::string pin_model;
  std::string ff_model;  // optional
  std::string robot;     // label of the BENCH lines
  // Short batches (about 0.1 ms): on a shared, loaded machine a long batch is often cut by
  // preemption, which inflates the median of the slower side; many short rounds do not.
  int rounds = 2001;
  int batch = 20;
  std::vector<std::string> frames{"l_sole", "r_sole"};
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: bench_dynamics <urdf> <pinocchio_model.txt> [--freeflyer-model FILE] "
                 "[--rounds N] [--batch K] [--frames a,b]\n");
    std::exit(2);
  }
  o.urdf = argv[1];
  o.pin_model = argv[2];
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--rounds") {
      o.rounds = std::max(1, std::atoi(argv[i + 1]));
    } else if (key == "--batch") {
      o.batch = std::max(1, std::atoi(argv[i + 1]));
    } else if (key == "--freeflyer-model") {
      o.ff_model = argv[i + 1];
    } else if (key == "--frames") {
      o.frames = split(argv[i + 1]);
    } else if (key == "--robot") {
      o.robot = argv[i + 1];
    } else {
      std::fprintf(stderr, "bench_dynamics: unknown option %s\n", key.c_str());
      std::exit(2);
    }
  }
  if (o.robot.empty()) {
    const size_t slash = o.urdf.find_last_of('/');
    o.robot = o.urdf.substr(slash == std::string::npos ? 0 : slash + 1);
    o.robot = o.robot.substr(0, o.robot.find_last_of('.'));
  }
  if (o.frames.size() != 2) {
    std::fprintf(stderr, "bench_dynamics: --frames needs exactly two frames\n");
    std::exit(2);
  }
  return o;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double relErr(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / std::max(1.0, b.norm());
}

/// Our coordinate i is Pinocchio's velocity (= position: only 1-dof joints) index perm[i].
std::vector<int> coordinateMap(const rt::RobotModel& ours, const pin::Model& ref) {
  std::vector<int> perm(ours.nq(), -1);
  int next_virtual = 0;
  for (int i = 0; i < ours.nq(); ++i) {
    const rt::JointInfo& j = ours.joints()[i];
    if (j.is_virtual) {
      perm[i] = next_virtual++;  // the composite root's coordinates come first in Pinocchio
      continue;
    }
    if (!ref.existJointName(j.name)) throw rt::ReachError("Pinocchio has no joint " + j.name);
    const auto id = ref.getJointId(j.name);
    if (ref.joints[id].nv() != 1 || ref.joints[id].nq() != 1)
      throw rt::ReachError("joint " + j.name + " is not a 1-dof joint in Pinocchio");
    perm[i] = ref.joints[id].idx_v();
  }
  return perm;
}

/// Pinocchio's side of the benchmark on one model (composite or FreeFlyer root).
struct Reference {
  Reference(const std::string& file, const std::vector<std::string>& frames)
      : model(load(file)), data(model) {
    for (const auto& f : frames)
      if (!model.existFrame(f)) throw rt::ReachError("Pinocchio has no frame " + f + " in " + file);
    p0 = model.getFrameId(frames[0]);
    p1 = model.getFrameId(frames[1]);
    J0 = pin::Data::Matrix6x::Zero(6, model.nv);
    J1 = J0;
    zero = Eigen::VectorXd::Zero(model.nv);
  }
  double mass(const Eigen::VectorXd& q) {
    pin::crba(model, data, q);
    data.M.triangularView<Eigen::StrictlyLower>() =
        data.M.transpose().triangularView<Eigen::StrictlyLower>();
    return data.M(model.nv - 1, 0);
  }
  double bias(const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
    pin::nonLinearEffects(model, data, q, v);
    return data.nle[0];
  }
  double full(const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
    double sum = mass(q) + bias(q, v);
    pin::computeJointJacobians(model, data, q);
    J0.setZero();
    J1.setZero();
    pin::getFrameJacobian(model, data, p0, pin::LOCAL_WORLD_ALIGNED, J0);
    pin::getFrameJacobian(model, data, p1, pin::LOCAL_WORLD_ALIGNED, J1);
    pin::forwardKinematics(model, data, q, v, zero);
    a0 = pin::getFrameClassicalAcceleration(model, data, p0, pin::LOCAL_WORLD_ALIGNED);
    a1 = pin::getFrameClassicalAcceleration(model, data, p1, pin::LOCAL_WORLD_ALIGNED);
    return sum + J0(2, model.nv - 1) + J1(2, model.nv - 1) + a0.linear()[2] + a1.linear()[2];
  }
  /// Jdot*qd of frame 0 or 1 after full(): [classical linear; angular], world orientation.
  Eigen::Matrix<double, 6, 1> jdotQd(int which) {
    const pin::FrameIndex f = which == 0 ? p0 : p1;
    Eigen::Matrix<double, 6, 1> out;
    out << (which == 0 ? a0 : a1).linear(),
        pin::getFrameAcceleration(model, data, f, pin::LOCAL_WORLD_ALIGNED).angular();
    return out;
  }

  static pin::Model load(const std::string& file) {
    pin::Model m;
    m.loadFromText(file);
    return m;
  }

  pin::Model model;  // before data: data is built from it
  pin::Data data;
  pin::FrameIndex p0 = 0, p1 = 0;
  pin::Data::Matrix6x J0, J1;
  pin::Motion a0, a1;
  Eigen::VectorXd zero;
};

}  // namespace

int main(int argc, char** argv) try {
  const Options opt = parse(argc, argv);

  // ---- the two models --------------------------------------------------------------------
  const auto ours = rt::RobotModel::fromUrdfFile(opt.urdf);
  rt::Workspace ws(*ours);
  Reference pr(opt.pin_model, opt.frames);
  const pin::Model& ref = pr.model;
  const int n = ours->nq();
  if (ref.nv != n || ref.nq != n) {
    std::fprintf(stderr, "bench_dynamics: ours n_q %d, Pinocchio nq %d nv %d\n", n,
                 static_cast<int>(ref.nq), static_cast<int>(ref.nv));
    return 1;
  }
  const std::vector<int> perm = coordinateMap(*ours, ref);
  const rt::FrameId f0 = ours->frameId(opt.frames[0]);
  const rt::FrameId f1 = ours->frameId(opt.frames[1]);

  // ---- random states within the joint limits (ours and the same in Pinocchio's order) -----
  std::mt19937 rng(20200701);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::VectorXd lo = ours->positionLowerLimits(), hi = ours->positionUpperLimits();
  std::vector<Eigen::VectorXd> qs, qds, pqs, pvs;
  for (int s = 0; s < kStates; ++s) {
    Eigen::VectorXd q(n), qd(n);
    for (int i = 0; i < n; ++i) {
      double a = lo[i], b = hi[i];
      if (!std::isfinite(a) || !std::isfinite(b) || b - a > 1e6) a = -M_PI, b = M_PI;
      q[i] = a + (b - a) * unit(rng);
      qd[i] = -2.0 + 4.0 * unit(rng);
    }
    if (ours->floatingBase()) q[4] = std::clamp(q[4], -1.3, 1.3);  // pitch away from +-pi/2
    Eigen::VectorXd pq(n), pv(n);
    for (int i = 0; i < n; ++i) pq[perm[i]] = q[i], pv[perm[i]] = qd[i];
    qs.push_back(q), qds.push_back(qd), pqs.push_back(pq), pvs.push_back(pv);
  }

  // The same states for a FreeFlyer root: base pose as a quaternion, joints mapped by name,
  // base velocity [linear; angular] taken from our base rates (same magnitudes; the timing does
  // not depend on the exact conversion).
  std::unique_ptr<Reference> ff;
  std::vector<Eigen::VectorXd> fqs, fvs;
  if (!opt.ff_model.empty()) {
    ff = std::make_unique<Reference>(opt.ff_model, opt.frames);
    const pin::Model& fm = ff->model;
    if (!ours->floatingBase() || fm.nq != n + 1 || fm.nv != n)
      throw rt::ReachError("FreeFlyer model does not match (nq " + std::to_string(fm.nq) + ")");
    for (int s = 0; s < kStates; ++s) {
      Eigen::VectorXd fq(n + 1), fv(n);
      const Eigen::VectorXd& q = qs[s];
      const Eigen::Quaterniond quat = Eigen::AngleAxisd(q[3], Eigen::Vector3d::UnitZ()) *
                                      Eigen::AngleAxisd(q[4], Eigen::Vector3d::UnitY()) *
                                      Eigen::AngleAxisd(q[5], Eigen::Vector3d::UnitX());
      fq.head<3>() = q.head<3>();
      fq.segment<4>(3) = quat.coeffs();  // x, y, z, w
      fv.head<6>() = qds[s].head<6>();
      for (int i = 6; i < n; ++i) {
        const auto& jm = fm.joints[fm.getJointId(ours->joints()[i].name)];
        fq[jm.idx_q()] = q[i];
        fv[jm.idx_v()] = qds[s][i];
      }
      fqs.push_back(fq), fvs.push_back(fv);
    }
  }

  // ---- the evaluations timed ---------------------------------------------------------------
  Eigen::MatrixXd M(n, n);
  Eigen::VectorXd b(n);
  rt::Matrix6Xd J0(6, n), J1(6, n);
  rt::Vector6d a0, a1;
  double sink = 0.0;  // keeps the results alive

  auto oursFull = [&](int s) {
    ours->update(ws, qs[s], qds[s]);
    ours->massMatrix(ws, M);
    ours->bias(ws, b);
    ours->frameJacobian(ws, f0, J0);
    ours->frameJacobian(ws, f1, J1);
    a0 = ours->frameJdotQd(ws, f0);
    a1 = ours->frameJdotQd(ws, f1);
    sink += M(n - 1, 0) + b[0] + J0(2, n - 1) + J1(2, n - 1) + a0[2] + a1[2];
  };
  auto refFull = [&](int s) { sink += pr.full(pqs[s], pvs[s]); };
  auto oursMass = [&](int s) {
    ours->update(ws, qs[s], qds[s]);
    ours->massMatrix(ws, M);
    sink += M(n - 1, 0);
  };
  auto refMass = [&](int s) { sink += pr.mass(pqs[s]); };
  auto oursBias = [&](int s) {
    ours->update(ws, qs[s], qds[s]);
    ours->bias(ws, b);
    sink += b[0];
  };
  auto refBias = [&](int s) { sink += pr.bias(pqs[s], pvs[s]); };
  auto ffFull = [&](int s) { sink += ff->full(fqs[s], fvs[s]); };
  auto ffMass = [&](int s) { sink += ff->mass(fqs[s]); };
  auto ffBias = [&](int s) { sink += ff->bias(fqs[s], fvs[s]); };

  // ---- the two agree (at one state), else the times mean nothing ---------------------------
  {
    Eigen::MatrixXd P(n, n);  // P x_ours = x_pinocchio
    P.setZero();
    for (int i = 0; i < n; ++i) P(perm[i], i) = 1.0;
    oursFull(3);
    refFull(3);
    const double e_m = relErr(M, P.transpose() * pr.data.M * P);
    const double e_b = relErr(b, P.transpose() * pr.data.nle);
    const double e_j = std::max(relErr(J0, pr.J0 * P), relErr(J1, pr.J1 * P));
    const double e_a = std::max(relErr(a0, pr.jdotQd(0)), relErr(a1, pr.jdotQd(1)));
    std::printf(
        "check: relative difference ours vs pinocchio at one state: M %.1e, b %.1e, "
        "J %.1e, Jdot*qd %.1e%s\n",
        e_m, e_b, e_j, e_a,
        std::max({e_m, e_b, e_j, e_a}) > 1e-8 ? "  (WARNING: they disagree)" : "");
  }

  // ---- interleaved timing -------------------------------------------------------------------
  using Clock = std::chrono::steady_clock;
  struct Pair {
    const char* name;
    std::function<void(int)> ours, ref, alt;   // alt: the FreeFlyer reference, if any
    std::vector<double> t_ours, t_ref, t_alt;  // microseconds per call, one per round
  };
  std::vector<Pair> pairs = {{"dynamics.full", oursFull, refFull, ffFull, {}, {}, {}},
                             {"dynamics.mass_matrix", oursMass, refMass, ffMass, {}, {}, {}},
                             {"dynamics.bias", oursBias, refBias, ffBias, {}, {}, {}}};
  auto timeBatch = [&](const std::function<void(int)>& f) {
    const auto t0 = Clock::now();
    for (int k = 0; k < opt.batch; ++k) f(k % kStates);
    const std::chrono::duration<double, std::micro> dt = Clock::now() - t0;
    return dt.count() / opt.batch;
  };
  for (auto& p : pairs) {  // warm-up: caches, page faults
    timeBatch(p.ours), timeBatch(p.ref);
    if (ff) timeBatch(p.alt);
  }
  for (int r = 0; r < opt.rounds; ++r) {
    for (auto& p : pairs) {
      if (r % 2 == 0) {
        p.t_ours.push_back(timeBatch(p.ours));
        p.t_ref.push_back(timeBatch(p.ref));
        if (ff) p.t_alt.push_back(timeBatch(p.alt));
      } else {
        if (ff) p.t_alt.push_back(timeBatch(p.alt));
        p.t_ref.push_back(timeBatch(p.ref));
        p.t_ours.push_back(timeBatch(p.ours));
      }
    }
  }
  std::printf("model: %s, n_q = %d, frames %s %s; %d rounds x %d calls, median per call\n",
              opt.urdf.c_str(), n, opt.frames[0].c_str(), opt.frames[1].c_str(), opt.rounds,
              opt.batch);
  for (const auto& p : pairs) {
    const double t_ours = median(p.t_ours), t_ref = median(p.t_ref);
    std::printf("BENCH %s robot=%s ours_us=%.3f ref=pinocchio ref_us=%.3f ratio=%.2f\n", p.name,
                opt.robot.c_str(), t_ours, t_ref, t_ours / t_ref);
  }
  for (const auto& p : pairs) {
    if (!ff) break;
    const double t_ours = median(p.t_ours), t_alt = median(p.t_alt);
    std::printf(
        "info: %s vs Pinocchio with a FreeFlyer root: ours_us=%.3f freeflyer_us=%.3f "
        "ratio=%.2f\n",
        p.name, t_ours, t_alt, t_ours / t_alt);
  }
  if (!std::isfinite(sink)) std::printf("(non-finite checksum)\n");
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "bench_dynamics: %s\n", e.what());
  return 1;
}
