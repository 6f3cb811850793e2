// A contiguous range of a cable's elements, as contact pairs and distributed loads name them.
#pragma once

#include <string>
#include <utility>

#include "ancf/core/error.hpp"
#include "ancf/core/types.hpp"

namespace ancf {

/// Elements [first, first + count) of a cable (count < 0: to the end).
struct ElementRange {
  Index first = 0;
  Index count = -1;
};

/// (first, count) of `range` in a cable of `elements` elements, count resolved. Throws
/// ModelError naming `owner` (e.g. "contact 'a'") and the cable when the range is empty or not
/// inside the cable.
[[nodiscard]] inline std::pair<Index, Index> resolve_element_range(const std::string& owner,
                                                                   const std::string& cable,
                                                                   ElementRange range,
                                                                   Index elements) {
  const Index count = range.count < 0 ? elements - range.first : range.count;
  if (range.first < 0 || count < 1 || range.first + count > elements)
    throw ModelError(owner + ": element range [" + std::to_string(range.first) + ", " +
                     std::to_string(range.first + count) + ") is not inside cable '" + cable +
                     "' (elements 0.." + std::to_string(elements - 1) + ")");
  return {range.first, count};
}

}  // namespace ancf
