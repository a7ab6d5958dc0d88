// SPDX-License-Identifier: LGPL-2.1-or-later
#include "robotctl-properties.h"

#include "robotctl-control-properties.h"

namespace robotctl {

const gstglue::PropertyTable<Settings, Shared> &properties() {
  static const gstglue::PropertyTable<Settings, Shared> table = [] {
    std::vector<gstglue::StartRule<Settings>> rules = linkRules();
    rules.push_back({controllerMismatch});
    return gstglue::PropertyTable<Settings, Shared>(
        gstglue::rowsOf<Row>(linkRows(), controlRows(), targetRows()), rules);
  }();
  return table;
}

}  // namespace robotctl
