// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack's GstPreset. GStreamer's default implementation saves and loads the presets (GstColorTrack.prs
// in $XDG_DATA_HOME/gstreamer-1.0/presets/, also looked for under $GST_PRESET_PATH); two things are changed:
//
// - Which properties a preset holds. The default takes every readable and writable property that is not
//   construct-only, the base classes' too: 'name' (a load would rename the element, refused once it is in a
//   bin), 'parent' and 'qos'. It would also take 'init-box' (a one-shot request, cleared once used: a preset
//   would re-pick a box of another scene) and 'template-location' (a path on the machine that saved it).
//   A colortrack preset holds colortrack's own settings and none of these.
// - Strings with a comma. The default save writes gst_value_serialize's "10\,50\,60" with
//   g_key_file_set_string (which doubles the backslash) and the default load reads it back with
//   g_key_file_get_value (which does not undo that): 'hsv-lower' came back as "10\,50\,60" (GStreamer 1.22).
//   After a load, the extra escape level is taken off the string properties. A value without a backslash is
//   left as it is, so this does nothing where GStreamer reads what it wrote; and colortrack's strings
//   (numbers and commas) never hold a backslash of their own, so taking one off cannot lose a character.
//   Until GStreamer does, each load logs the property table's "the element will fail to start" warning for
//   the escaped strings it set first.
#include "colortrack-preset.h"

#include <cstring>
#include <string>

namespace {

gboolean (*default_load_preset)(GstPreset *preset, const gchar *name) = nullptr;

bool excluded(const char *name) {
  return std::strcmp(name, "init-box") == 0 || std::strcmp(name, "template-location") == 0;
}

gchar **colortrack_property_names(GstPreset *preset) {
  guint n = 0;
  GParamSpec **specs = g_object_class_list_properties(G_OBJECT_GET_CLASS(preset), &n);
  GPtrArray *names = g_ptr_array_new();
  for (guint i = 0; i < n; ++i) {
    const GParamSpec *spec = specs[i];
    const bool readWrite = (spec->flags & G_PARAM_READWRITE) == G_PARAM_READWRITE;
    if (spec->owner_type != G_OBJECT_TYPE(preset) || !readWrite ||
        (spec->flags & G_PARAM_CONSTRUCT_ONLY) != 0 || excluded(spec->name))
      continue;
    g_ptr_array_add(names, g_strdup(spec->name));
  }
  g_free(specs);
  g_ptr_array_add(names, nullptr);
  return reinterpret_cast<gchar **>(g_ptr_array_free(names, FALSE));
}

// "\x" -> "x": the escape level the keyfile added and the default load left.
std::string dropEscapes(const char *s) {
  std::string out;
  for (const char *p = s; *p != '\0'; ++p) {
    if (*p == '\\' && p[1] != '\0') ++p;
    out += *p;
  }
  return out;
}

gboolean colortrack_load_preset(GstPreset *preset, const gchar *name) {
  if (!default_load_preset(preset, name)) return FALSE;
  gchar **props = gst_preset_get_property_names(preset);
  for (gchar **p = props; p != nullptr && *p != nullptr; ++p) {
    GParamSpec *spec = g_object_class_find_property(G_OBJECT_GET_CLASS(preset), *p);
    if (spec == nullptr || spec->value_type != G_TYPE_STRING) continue;
    gchar *value = nullptr;
    g_object_get(preset, *p, &value, nullptr);
    if (value != nullptr && std::strchr(value, '\\') != nullptr)
      g_object_set(preset, *p, dropEscapes(value).c_str(), nullptr);
    g_free(value);
  }
  g_strfreev(props);
  return TRUE;
}

}  // namespace

void gst_color_track_preset_init(GstPresetInterface *iface) {
  default_load_preset = iface->load_preset;
  iface->get_property_names = colortrack_property_names;
  iface->load_preset = colortrack_load_preset;
}
