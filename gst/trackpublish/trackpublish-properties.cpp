// SPDX-License-Identifier: LGPL-2.1-or-later
#include "trackpublish-properties.h"

#include "trackpublish-output.h"

namespace trackpublish {

const gstglue::PropertyTable<Settings> &properties() {
  // Nothing to publish to is a missing resource, as before the table judged it.
  static const gstglue::PropertyTable<Settings> table(
      settingRows(),
      {{checkSomeOutput, gstglue::StartRule<Settings>::Severity::Error, GST_RESOURCE_ERROR_NOT_FOUND}});
  return table;
}

}  // namespace trackpublish
