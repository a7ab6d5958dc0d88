// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl's engine: the controller that turns each buffer's target into a command, made at start and kept
// up to date with the settings that change while playing, and the lock on the target it follows.
#pragma once

#include <memory>

#include "colortrack/controller.hpp"
#include "colortrack/target_lock.hpp"
#include "robotctl-settings.h"

namespace robotctl {

class ControllerStage {
 public:
  // The controller the start's settings ask for; its axes (the protocol's) stay fixed until the next start.
  explicit ControllerStage(const Settings &atStart);

  // Settings whose controller or failsafe changed. A new gain or limit keeps the ramp and the lost-target
  // hold; only another kind of controller starts afresh.
  void apply(const Settings &changed);
  // After a flush or the "reset" signal: the controller forgets its past and the target is let go.
  void reset();

  colortrack::TargetLock &lock() { return lock_; }
  colortrack::DriveOutput decide(const colortrack::Observation &observation) {
    return controller_->update(observation);
  }

 private:
  std::unique_ptr<colortrack::RobotController> controller_;
  colortrack::ControllerKind kind_;  // of `controller_`
  colortrack::ControlAxes axes_;     // from the protocol, read at start
  colortrack::TargetLock lock_;
};

}  // namespace robotctl
