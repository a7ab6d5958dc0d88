// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl's property table: its rows in the order gst-inspect-1.0 lists them, and its start rules.
#pragma once

#include "robotctl-settings.h"

namespace robotctl {

const gstglue::PropertyTable<Settings, Shared> &properties();

}  // namespace robotctl
