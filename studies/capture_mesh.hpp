// The capture scene's rope mesh as a study parameter (ancf-capture --elements, the capture cases
// of ancf-study-scaling): every rope ([[cable]] or [[rod]]) gets `elements` elements and the
// rope–rope candidate ranges follow (the middle halves of both ropes, as in the scene file at 24
// elements).
#pragma once

#include <toml++/toml.h>
#include <cstdint>

namespace ancf::studies {

inline void set_capture_rope_elements(toml::table& root, long elements) {
  for (const char* kind : {"cable", "rod"})  // the ropes: [[cable]] or, capture_rod.toml, [[rod]]
    if (toml::array* ropes = root[kind].as_array())
      for (toml::node& c : *ropes)
        c.as_table()->insert_or_assign("elements", static_cast<int64_t>(elements));
  if (toml::array* contacts = root["contact"].as_array())
    for (toml::node& c : *contacts) {
      toml::table& t = *c.as_table();
      if (!t.contains("other_cable")) continue;
      const toml::array range{static_cast<int64_t>(elements / 4),
                              static_cast<int64_t>(elements / 2)};
      t.insert_or_assign("elements", range);
      t.insert_or_assign("other_elements", range);
    }
}

}  // namespace ancf::studies
