/// \file push_envelope.cpp
/// The push-recovery sweep and its figure (see the header).

#include "reach_trajopt/walk/push_envelope.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <mutex>
#include <sstream>
#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {
namespace {
constexpr double kStandingDuration = 3.0;  ///< how long the standing reference stands [s]

/// One walk of the sweep: `w`'s push (by the grid's protocol) and seed; its outcome into `w`.
void runPushWalk(const WalkSetup& setup, const std::string& urdf_path, const WalkingPolicy& policy,
                 const PushGrid& grid, PushWalk& w) {
  WalkSetup run = setup;
  run.walk.policy = policy;
  run.walk.steps = grid.steps;
  run.walk.forward_speed = grid.forward_speed;
  if (grid.protocol == PushGrid::Protocol::kStanding)
    run.walk.initial_com_velocity = w.push;
  else
    run.walk.midswing_push = w.push;
  run.walk.seed = grid.seeds[w.seed];
  if (grid.standing) {
    run.walk.steps = 0;
    run.walk.settle_duration = kStandingDuration;
  }
  const WalkResult r = run.experiment(urdf_path)->run();
  w.fell = r.fell || r.steps < run.walk.steps;
  w.steps = r.steps;
  w.end_reason = r.end_reason;
  w.wall_s = r.wall_time;
}

}  // namespace

void PushGrid::validate() const {
  if (directions < 1 || directions > 64)
    throw RequestError("push grid: directions must be in [1, 64], got " +
                       std::to_string(directions));
  if (magnitudes.empty() || magnitudes.size() > 64)
    throw RequestError("push grid: 1 to 64 magnitudes, got " + std::to_string(magnitudes.size()));
  for (std::size_t i = 0; i < magnitudes.size(); ++i) {
    if (!(magnitudes[i] > 0.0) || !std::isfinite(magnitudes[i]) || magnitudes[i] > 10.0)
      throw RequestError("push grid: magnitudes must be in (0, 10] m/s");
    if (i > 0 && !(magnitudes[i] > magnitudes[i - 1]))
      throw RequestError("push grid: magnitudes must increase");
  }
  if (seeds.empty() || seeds.size() > 64)
    throw RequestError("push grid: 1 to 64 seeds, got " + std::to_string(seeds.size()));
  if (!std::isfinite(forward_speed) || std::abs(forward_speed) > 2.0)
    throw RequestError("push grid: forward_speed must be in [-2, 2] m/s");
  if (steps < 1 || steps > 1000)
    throw RequestError("push grid: steps must be in [1, 1000], got " + std::to_string(steps));
}

const char* PushGrid::protocolName() const {
  return protocol == Protocol::kMidswing ? "midswing" : "standing";
}

double PushGrid::angle(int direction) const { return 2.0 * M_PI * direction / directions; }

Eigen::Vector2d PushGrid::push(int direction, int magnitude) const {
  const double a = angle(direction), m = magnitudes[magnitude];
  // Exact zeros on the axes, so that a lateral push has no forward part.
  const auto clean = [](double v) { return std::abs(v) < 1e-12 ? 0.0 : v; };
  return Eigen::Vector2d(clean(m * std::cos(a)), clean(m * std::sin(a)));
}

int PushEnvelope::survived() const {
  return static_cast<int>(
      std::count_if(walks.begin(), walks.end(), [](const PushWalk& w) { return !w.fell; }));
}

double PushEnvelope::radius(int direction) const {
  double r = 0.0;
  for (int m = 0; m < static_cast<int>(grid.magnitudes.size()); ++m) {
    for (const PushWalk& w : walks)
      if (w.direction == direction && w.magnitude == m && w.fell) return r;
    r = grid.magnitudes[m];
  }
  return r;
}

double PushEnvelope::maxLateral() const {
  if (grid.directions % 4 != 0) return -1.0;
  return std::max(radius(grid.directions / 4), radius(3 * grid.directions / 4));
}

double PushEnvelope::maxForward() const { return radius(0); }

std::string PushEnvelope::benchLine() const {
  std::ostringstream os;
  os.precision(3);
  double wall = 0.0;
  for (const PushWalk& w : walks) wall += w.repeated ? 0.0 : w.wall_s;
  os << "BENCH walk.envelope preset=" << (grid.standing ? "standing" : policy.name.c_str())
     << " protocol=" << grid.protocolName() << " forward_mps=" << grid.forward_speed
     << " pushes=" << pushes() << " survived=" << survived() << " max_lateral_mps=" << maxLateral()
     << " max_forward_mps=" << maxForward() << " radii_mps=";
  for (int d = 0; d < grid.directions; ++d) os << (d ? "/" : "") << radius(d);
  if (static_cast<int>(capture.size()) == grid.directions) {
    const auto list = [&](const char* key, auto value) {
      os << " " << key << "=";
      for (int d = 0; d < grid.directions; ++d) os << (d ? "/" : "") << value(d);
    };
    list("capture0_mps", [&](int d) { return capture[d].zero_step; });
    list("capture1_mps", [&](int d) { return capture[d].one_step; });
    list("captureN_mps", [&](int d) { return capture[d].n_step; });
    list("fraction_of_capture1", [&](int d) { return radius(d) / capture[d].one_step; });
  }
  os << " directions=" << grid.directions << " magnitudes_mps=";
  for (std::size_t m = 0; m < grid.magnitudes.size(); ++m)
    os << (m ? "/" : "") << grid.magnitudes[m];
  os << " seeds=" << grid.seeds.size() << " steps=" << (grid.standing ? 0 : grid.steps)
     << " walks_wall_s=" << wall;
  // Paying for the plans' time: marked, beside the reference's lines (pause, unmarked).
  if (plan_latency != "pause" && !grid.standing) os << " plan_latency=" << plan_latency;
  if (!grid.standing) os << " " << policy.definition();
  return os.str();
}

PushEnvelope sweepPushes(const WalkSetup& setup, const std::string& urdf_path,
                         const WalkingPolicy& policy, const PushGrid& grid, int jobs,
                         const std::function<void(const PushWalk&)>& on_walk) {
  grid.validate();
  policy.validate();
  PushEnvelope env;
  env.policy = policy;
  env.grid = grid;
  env.plan_latency = setup.walk.planLatencyName();
  const CaptureModel capture_model =
      CaptureModel::fromConfigs(setup.tvr, setup.contact, setup.walk.single_support_duration);
  for (int d = 0; d < grid.directions; ++d)
    env.capture.push_back(captureLimits(capture_model, grid.angle(d)));
  const int n_dir = grid.directions, n_mag = static_cast<int>(grid.magnitudes.size()),
            n_seed = static_cast<int>(grid.seeds.size());
  // Only the reachability check draws random samples: other policies repeat bit for bit.
  const bool draws = policy.check == WalkingPolicy::FootholdCheck::kReachability && !grid.standing;
  const int seeds_run = draws ? n_seed : 1;
  for (int d = 0; d < n_dir; ++d)
    for (int m = 0; m < n_mag; ++m)
      for (int s = 0; s < n_seed; ++s) {
        PushWalk w;
        w.direction = d;
        w.magnitude = m;
        w.seed = s;
        w.push = grid.push(d, m);
        w.repeated = s >= seeds_run;
        env.walks.push_back(w);
      }
  std::vector<int> to_run;
  for (int i = 0; i < static_cast<int>(env.walks.size()); ++i)
    if (!env.walks[i].repeated) to_run.push_back(i);

  std::atomic<int> next{0};
  std::mutex report;
  std::vector<std::string> errors;
  const auto worker = [&]() {
#ifdef _OPENMP
    omp_set_num_threads(1);  // one walk per thread; the sampler's result does not depend on it
#endif
    for (int k = next++; k < static_cast<int>(to_run.size()); k = next++) {
      PushWalk& w = env.walks[to_run[k]];
      try {
        runPushWalk(setup, urdf_path, policy, grid, w);
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(report);
        errors.push_back(e.what());
        continue;
      }
      if (on_walk) {
        std::lock_guard<std::mutex> lock(report);
        on_walk(w);
      }
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < std::max(1, jobs); ++j) threads.emplace_back(worker);
  for (std::thread& t : threads) t.join();
  if (!errors.empty()) throw ReachError("push sweep: a walk failed: " + errors.front());
  for (PushWalk& w : env.walks) {
    if (!w.repeated) continue;
    const PushWalk& first = env.walks[&w - env.walks.data() - w.seed];
    w.fell = first.fell;
    w.steps = first.steps;
    w.end_reason = first.end_reason;
    w.wall_s = first.wall_s;
  }
  return env;
}

std::string envelopeSvg(const std::vector<PushEnvelope>& envelopes) {
  const double panel = 300.0, r_max = 110.0;
  const int n = static_cast<int>(envelopes.size());
  std::ostringstream os;
  os.precision(4);
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << panel * std::max(1, n)
     << "\" height=\"" << panel + 40 << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
     << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (int p = 0; p < n; ++p) {
    const PushEnvelope& e = envelopes[p];
    const double cx = panel * p + panel / 2, cy = panel / 2 + 20;
    const double m_max = e.grid.magnitudes.back();
    // Screen: +x (forward) up, +y (left) to the left, as seen from above with the robot
    // facing up.
    const auto at = [&](double angle, double mag, double& x, double& y) {
      x = cx - std::sin(angle) * mag / m_max * r_max;
      y = cy - std::cos(angle) * mag / m_max * r_max;
    };
    os << "<text x=\"" << cx << "\" y=\"18\" text-anchor=\"middle\" font-weight=\"bold\">"
       << e.policy.name << ": " << e.survived() << "/" << e.pushes() << " survived</text>\n";
    for (double mag : e.grid.magnitudes) {
      os << "<circle cx=\"" << cx << "\" cy=\"" << cy << "\" r=\"" << mag / m_max * r_max
         << "\" fill=\"none\" stroke=\"#ccc\"/>\n";
      os << "<text x=\"" << cx + 3 << "\" y=\"" << cy - mag / m_max * r_max + 11
         << "\" fill=\"#888\" font-size=\"9\">" << mag << "</text>\n";
    }
    for (int d = 0; d < e.grid.directions; ++d) {
      double x, y;
      at(e.grid.angle(d), m_max * 1.08, x, y);
      os << "<line x1=\"" << cx << "\" y1=\"" << cy << "\" x2=\"" << x << "\" y2=\"" << y
         << "\" stroke=\"#eee\"/>\n";
    }
    // The envelope polygon.
    os << "<polygon fill=\"#4a90d9\" fill-opacity=\"0.2\" stroke=\"#4a90d9\" points=\"";
    for (int d = 0; d < e.grid.directions; ++d) {
      double x, y;
      at(e.grid.angle(d), e.radius(d), x, y);
      os << x << "," << y << " ";
    }
    os << "\"/>\n";
    for (int d = 0; d < e.grid.directions; ++d)
      for (int m = 0; m < static_cast<int>(e.grid.magnitudes.size()); ++m) {
        int ok = 0, all = 0;
        for (const PushWalk& w : e.walks)
          if (w.direction == d && w.magnitude == m) {
            ++all;
            ok += !w.fell;
          }
        const char* color = ok == all ? "#2a9d3a" : (ok > 0 ? "#e0a800" : "#d62828");
        double x, y;
        at(e.grid.angle(d), e.grid.magnitudes[m], x, y);
        os << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"5\" fill=\"" << color << "\"/>\n";
      }
    os << "<text x=\"" << cx << "\" y=\"" << cy - r_max - 16
       << "\" text-anchor=\"middle\" fill=\"#555\" font-size=\"10\">+x (forward)</text>\n"
       << "<text x=\"" << cx - r_max - 14 << "\" y=\"" << cy + 4
       << "\" text-anchor=\"end\" fill=\"#555\" font-size=\"10\">+y</text>\n";
  }
  os << "<text x=\"8\" y=\"" << panel + 34
     << "\" font-size=\"10\" fill=\"#333\">push = initial CoM velocity [m/s], rings = "
        "magnitudes; green: survived every seed, amber: some, red: fell; blue: envelope "
        "(every smaller push survived)</text>\n</svg>\n";
  return os.str();
}

}  // namespace reach_trajopt
