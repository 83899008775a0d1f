#include "reach_trajopt/contact/contact_sequence.h"

#include <cmath>
#include <sstream>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

ContactSequence::ContactSequence(std::vector<ContactPhase> phases) {
  for (const auto& p : phases) append(p);
}

ContactSequence ContactSequence::walking(int steps, Side first_stance, double ss_duration,
                                         double ds_duration) {
  if (steps < 0) throw RequestError("ContactSequence::walking: steps must be >= 0");
  ContactSequence seq;
  seq.append({ContactMode::doubleSupport(), ds_duration});
  Side stance = first_stance;
  for (int k = 0; k < steps; ++k) {
    seq.append({ContactMode::singleSupport(stance), ss_duration});
    seq.append({ContactMode::doubleSupport(), ds_duration});
    stance = opposite(stance);
  }
  return seq;
}

void ContactSequence::append(const ContactPhase& phase) {
  const int i = size();
  if (!std::isfinite(phase.duration) || phase.duration <= 0.0) {
    std::ostringstream os;
    os << "contact sequence phase " << i << " (" << phase.mode.name()
       << "): duration must be positive and finite, got " << phase.duration << " s";
    throw RequestError(os.str());
  }
  if (phase.mode.contactCount() == 0) {
    throw RequestError("contact sequence phase " + std::to_string(i) +
                       ": flight phases are not supported (no sole in contact)");
  }
  if (!phases_.empty()) {
    const ContactMode& prev = phases_.back().mode;
    if (prev == phase.mode) {
      throw RequestError("contact sequence phase " + std::to_string(i) + ": mode " +
                         phase.mode.name() + " repeats the previous phase (merge the durations)");
    }
    const bool keeps_contact = (prev.left && phase.mode.left) || (prev.right && phase.mode.right);
    if (!keeps_contact) {
      throw RequestError("contact sequence phase " + std::to_string(i) + ": switch " + prev.name() +
                         " -> " + phase.mode.name() +
                         " has no sole in contact through it (insert a DS phase)");
    }
  }
  start_times_.push_back(totalDuration());
  phases_.push_back(phase);
}

const ContactPhase& ContactSequence::phase(int i) const {
  if (i < 0 || i >= size()) {
    throw RequestError("contact sequence: phase index " + std::to_string(i) + " outside [0, " +
                       std::to_string(size()) + ")");
  }
  return phases_[i];
}

double ContactSequence::startTime(int i) const {
  phase(i);  // range check
  return start_times_[i];
}

double ContactSequence::totalDuration() const {
  return phases_.empty() ? 0.0 : start_times_.back() + phases_.back().duration;
}

int ContactSequence::phaseIndexAt(double t) const {
  const double total = totalDuration();
  if (empty() || !(t >= 0.0 && t <= total)) {
    std::ostringstream os;
    os << "contact sequence: time " << t << " s outside [0, " << total << "] s";
    throw RequestError(os.str());
  }
  int lo = 0;
  for (int i = 1; i < size(); ++i) {
    if (start_times_[i] <= t)
      lo = i;
    else
      break;
  }
  return lo;
}

}  // namespace reach_trajopt
