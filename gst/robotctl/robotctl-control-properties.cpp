// SPDX-License-Identifier: LGPL-2.1-or-later
#include "robotctl-control-properties.h"

#include <cmath>

#include "colortrack/command_writer.hpp"

namespace robotctl {

namespace {

using gstglue::Apply;
using Def = Row;
using colortrack::ControllerSettings;
using colortrack::FailsafeSettings;
using Change = Settings::Change;

}  // namespace

colortrack::Status controllerMismatch(const Settings &s) {
  const colortrack::ControllerSettings c = controllerSettings(s);
  if (colortrack::lawFits(c.kind, c.axes)) return {};
  return colortrack::Status::failure(
      "controller=zone cannot drive a gimbal (protocol=mavlink mavlink-mode=gimbal): its commands are one "
      "motion at a time at a fixed speed. Use controller=auto (the default) or controller=proportional");
}

namespace {

colortrack::Status checkControllerValue(const PropertyStore &store, const GValue *v) {
  if (!store.running) return {};
  Settings s = store.settings;
  s.controller.kind = static_cast<colortrack::ControllerKind>(g_value_get_enum(v));
  return controllerMismatch(s);
}

// How commands are decided: from the next buffer.
std::vector<Def> controllerRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_enum("controller", "Controller",
                                 "How commands are decided; zone cannot drive a gimbal (mavlink-mode=gimbal)",
                                 GST_TYPE_ROBOT_CTL_CONTROLLER, static_cast<gint>(Settings{}.controller.kind),
                                 f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::kind>()
          .checking(checkControllerValue),
      Def::live([](GParamFlags f) {
        return g_param_spec_enum("distance-cue", "Distance cue", "What tells how far the target is",
                                 GST_TYPE_ROBOT_CTL_DISTANCE_CUE,
                                 static_cast<gint>(Settings{}.controller.distanceCue), f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::distanceCue>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("set-point", "Set-point",
                                   "Wanted distance cue: box height (or box bottom) as a fraction of the "
                                   "frame height",
                                   0.01, 1.0, ControllerSettings{}.setPoint, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::setPoint>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_boolean("set-point-at-start", "Set-point at start",
                                    "Keep the distance cue the target had when first confirmed (after start, "
                                    "a flush, or turning this on) instead of set-point: the robot holds the "
                                    "distance it was at, whatever share of the object the box covers",
                                    ControllerSettings{}.setPointAtStart, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::setPointAtStart>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("turn-deadband", "Turn deadband",
                                   "Horizontal offset (fraction of half the frame width) within "
                                   "which the target counts as centred",
                                   0.0, 1.0, ControllerSettings{}.turnDeadband, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::turnDeadband>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("distance-deadband", "Distance deadband",
                                   "Relative distance error within which the distance counts as right", 0.0,
                                   1.0, ControllerSettings{}.distanceDeadband, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::distanceDeadband>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("hysteresis", "Hysteresis",
                                   "Zone controller: how far inside a deadband the error must come "
                                   "back before a turn or drive ends",
                                   0.0, 1.0, ControllerSettings{}.hysteresis, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::hysteresis>(),
  };
}

// The proportional controller's gains.
std::vector<Def> gainRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_double("turn-gain", "Turn gain",
                                   "Proportional controller: angular speed per unit horizontal offset, 0-100",
                                   0.0, 100.0, ControllerSettings{}.turnGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::turnGain>()
          .refusing(gstglue::refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("drive-gain", "Drive gain",
                                   "Proportional controller: linear speed per unit relative distance "
                                   "error, 0-100",
                                   0.0, 100.0, ControllerSettings{}.driveGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::driveGain>()
          .refusing(gstglue::refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "turn-integral-gain", "Turn integral gain",
            "Proportional controller: angular speed per unit horizontal offset held for a second, 0-100 "
            "(removes "
            "the lag behind a target moving sideways; frozen while the turn is limited)",
            0.0, 100.0, ControllerSettings{}.turnIntegralGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::turnIntegralGain>()
          .refusing(gstglue::refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "drive-integral-gain", "Drive integral gain",
            "Proportional controller: linear speed per unit relative distance error held for a second, 0-100 "
            "(removes the lag behind a target moving away or closer; frozen while the speed is limited)",
            0.0, 100.0, ControllerSettings{}.driveIntegralGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::driveIntegralGain>()
          .refusing(gstglue::refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "turn-rate-gain", "Turn rate gain",
            "Proportional controller: angular speed per unit of horizontal offset change per second, 0-100 "
            "(reacts to the target's sideways motion; damps the turn)",
            0.0, 100.0, ControllerSettings{}.turnRateGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::turnRateGain>()
          .refusing(gstglue::refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "drive-rate-gain", "Drive rate gain",
            "Proportional controller: linear speed per unit of relative distance error change per second, "
            "0-100 (reacts to the target moving away or closer; damps the approach)",
            0.0, 100.0, ControllerSettings{}.driveRateGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::driveRateGain>()
          .refusing(gstglue::refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "latency", "Latency",
            "Zone controller: seconds from a command to the wheels (the robot's delay plus about half the "
            "send period 1/rate). A turn ends this much early and, near the centre, turns are single "
            "decisions each followed by this long without a turn, so the robot does not swing across the "
            "centre. 0: no such rule (the paper's controller)",
            0.0, 2.0, ControllerSettings{}.latency, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::latency>(),
  };
}

// The limits of every command.
std::vector<Def> limitRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_double("max-linear", "Maximum linear speed",
                                   "Largest forward/backward speed (fraction of full speed); the zone "
                                   "controller's driving speed",
                                   0.0, 1.0, ControllerSettings{}.maxLinear, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::maxLinear>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("max-angular", "Maximum angular speed",
                                   "Largest turn speed (fraction of full wheel speed); the zone "
                                   "controller's turning speed",
                                   0.0, 1.0, ControllerSettings{}.maxAngular, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::maxAngular>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("max-linear-accel", "Maximum linear acceleration",
                                   "Proportional controller: largest change of the linear speed "
                                   "per second (0 = unlimited)",
                                   0.0, 1000.0, ControllerSettings{}.maxLinearAccel, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::maxLinearAccel>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("max-angular-accel", "Maximum angular acceleration",
                                   "Proportional controller: largest change of the angular "
                                   "speed per second (0 = unlimited)",
                                   0.0, 1000.0, ControllerSettings{}.maxAngularAccel, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::maxAngularAccel>(),
  };
}

// The failsafe.
std::vector<Def> failsafeRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_uint(
            "lost-timeout", "Lost timeout",
            "Milliseconds without a confirmed target, or without any buffer, before the target counts "
            "as lost and the robot stops (or search-turns); without a confirmed target it keeps its drive "
            "for the first half, then stands still, and never keeps its turn",
            1, 600000, static_cast<guint>(std::lround(FailsafeSettings{}.lostTimeout * 1000)), f);
      })
          .marks({Change::Controller})
          .accessors(
              [](const Settings &s, GValue *v) {
                g_value_set_uint(v, static_cast<guint>(std::lround(s.failsafe.lostTimeout * 1000)));
              },
              [](Settings &s, const GValue *v) { s.failsafe.lostTimeout = g_value_get_uint(v) / 1000.0; }),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("min-score", "Minimum score",
                                   "A target with a lower score counts as not seen", 0.0, 1.0,
                                   FailsafeSettings{}.minScore, f);
      })
          .marks({Change::Controller})
          .field<&Settings::failsafe, &FailsafeSettings::minScore>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_boolean("search-turn", "Search turn",
                                    "After lost-timeout turn slowly towards where the target was last "
                                    "seen instead of standing still",
                                    FailsafeSettings{}.searchTurn, f);
      })
          .marks({Change::Controller})
          .field<&Settings::failsafe, &colortrack::FailsafeSettings::searchTurn>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("search-speed", "Search speed",
                                   "Angular speed of the search turn (fraction of full wheel speed); only "
                                   "used with search-turn=true",
                                   0.0, 1.0, FailsafeSettings{}.searchSpeed, f);
      })
          .marks({Change::Controller})
          .field<&Settings::failsafe, &FailsafeSettings::searchSpeed>(),
  };
}

// The writer is told under the object lock, which it never takes: it only holds its own lock briefly.
void holdAccepted(PropertyStore &store) {
  if (store.shared.writer) store.shared.writer->setHeld(store.settings.hold);
}

// A person's STOP (a button on a page, a key in an application): at once, not from the next buffer.
std::vector<Def> holdRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_boolean(
            "hold", "Hold",
            "Stop the robot at once and send only stop until set back to false (tracking and decisions go "
            "on, and are sent again from the release); may be set at any time, also before start",
            Settings{}.hold, f);
      })
          .field<&Settings::hold>()
          .onAccepted(holdAccepted),
  };
}

}  // namespace

std::vector<Row> controlRows() {
  return gstglue::rowsOf<Def>(controllerRows(), gainRows(), limitRows(), failsafeRows(), holdRows());
}

}  // namespace robotctl
