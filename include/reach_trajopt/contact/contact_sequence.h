#pragma once
/// \file contact_sequence.h
/// The sequence of contact modes m_0, m_1, ... with their durations that the stepping loop of
/// Sec. IV walks through: DS -> SS-L -> DS -> SS-R -> DS ... (no flight phase).

#include <vector>

#include "reach_trajopt/contact/contact_mode.h"

namespace reach_trajopt {

/// One phase: a contact mode held for `duration` seconds.
struct ContactPhase {
  ContactMode mode;
  double duration = 0.0;  ///< [s], > 0
};

/// A timed sequence of contact modes. Valid sequences have positive finite durations, no flight
/// phase, and every switch keeps at least one sole in contact through it (a switch from SS-L
/// straight to SS-R would need a flight instant; a switch to the same mode is no switch).
class ContactSequence {
 public:
  ContactSequence() = default;
  /// Throws ReachError when the phases do not form a valid sequence (see class comment).
  explicit ContactSequence(std::vector<ContactPhase> phases);

  /// The walking pattern DS, SS(first_stance), DS, SS(other), ..., DS with `steps` single
  /// support phases. \param ss_duration, ds_duration [s] > 0. Throws ReachError on bad input.
  static ContactSequence walking(int steps, Side first_stance, double ss_duration,
                                 double ds_duration);

  /// Appends a phase; throws ReachError when it would make the sequence invalid.
  void append(const ContactPhase& phase);

  int size() const { return static_cast<int>(phases_.size()); }
  bool empty() const { return phases_.empty(); }
  const ContactPhase& phase(int i) const;
  const std::vector<ContactPhase>& phases() const { return phases_; }
  /// Start time of phase i [s] (phase 0 starts at 0).
  double startTime(int i) const;
  double totalDuration() const;  ///< [s]
  /// Index of the phase active at time t [s] (t in [start, start + duration), the last phase
  /// also owns t = total). Throws ReachError for t outside [0, total] or NaN.
  int phaseIndexAt(double t) const;
  const ContactMode& modeAt(double t) const { return phases_[phaseIndexAt(t)].mode; }

 private:
  std::vector<ContactPhase> phases_;
  std::vector<double> start_times_;
};

}  // namespace reach_trajopt
