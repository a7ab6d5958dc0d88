// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl's properties of how commands are decided (the controller, its gains and limits, the failsafe):
// the rows of its table that apply from the next buffer, and the rule that joins them to the protocol.
#pragma once

#include <string>
#include <vector>

#include "robotctl-settings.h"

namespace robotctl {

std::vector<Row> controlRows();
// Whether `controller` can drive what the protocol drives (not zone and a gimbal), or why not: a start rule,
// and checked again when `controller` is set while running.
colortrack::Status controllerMismatch(const Settings &settings);

}  // namespace robotctl
