#include "pipelines/compare/variant_list.h"

#include <algorithm>
#include <stdexcept>

namespace hsmap {

const std::vector<Variant>& allCompareVariants() {
  static const std::vector<Variant> variants = {Variant::stacked, Variant::planar, Variant::sequential,
                                                Variant::joint};
  return variants;
}

std::vector<Variant> parseVariantList(const std::string& text) {
  std::string names;
  for (Variant variant : allCompareVariants()) names += (names.empty() ? "" : ", ") + std::string(toString(variant));
  std::vector<Variant> variants;
  std::size_t start = 0;
  while (start <= text.size() && !text.empty()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, end - start);
    const auto known = std::find_if(allCompareVariants().begin(), allCompareVariants().end(),
                                    [&](Variant v) { return name == toString(v); });
    if (known == allCompareVariants().end()) {
      throw std::invalid_argument("--variants: unknown variant '" + name + "' in '" + text +
                                  "'; expected names among " + names + ", separated by commas");
    }
    if (std::find(variants.begin(), variants.end(), *known) != variants.end()) {
      throw std::invalid_argument("--variants: '" + name + "' is listed twice in '" + text + "'");
    }
    variants.push_back(*known);
    start = end + 1;
  }
  if (variants.empty()) throw std::invalid_argument("--variants: expected at least one variant, got ''");
  return variants;
}

}  // namespace hsmap
