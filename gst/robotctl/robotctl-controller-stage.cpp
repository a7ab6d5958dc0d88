// SPDX-License-Identifier: LGPL-2.1-or-later
#include "robotctl-controller-stage.h"

namespace robotctl {

ControllerStage::ControllerStage(const Settings &atStart) {
  const colortrack::ControllerSettings controller = controllerSettings(atStart);
  controller_ = std::make_unique<colortrack::RobotController>(controller, atStart.failsafe);
  kind_ = controller.kind;
  axes_ = controller.axes;
  lock_.setPolicy(atStart.lockOn);
}

void ControllerStage::apply(const Settings &now) {
  colortrack::ControllerSettings controller = now.controller;
  controller.axes = axes_;
  if (controller.kind != kind_) {
    controller_ = std::make_unique<colortrack::RobotController>(controller, now.failsafe);
    kind_ = controller.kind;
  } else {
    controller_->setSettings(controller, now.failsafe);
  }
}

void ControllerStage::reset() {
  controller_->reset();
  lock_.release();
}

}  // namespace robotctl
