// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish's property table: its rows in the order gst-inspect-1.0 lists them, and its start rule (some
// output is set, from the output table).
#pragma once

#include "trackpublish-settings.h"

namespace trackpublish {

const gstglue::PropertyTable<Settings> &properties();

}  // namespace trackpublish
