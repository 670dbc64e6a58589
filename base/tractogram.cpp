#include "base/tractogram.h"

namespace curette {

void Tractogram::append(const Tractogram& other) {
    bool sameScalars = scalarNames == other.scalarNames || points.empty();
    bool sameProperties = propertyNames == other.propertyNames || points.empty();
    if (points.empty()) scalarNames = other.scalarNames, propertyNames = other.propertyNames;
    if (!sameScalars) scalarNames.clear(), scalars.clear();
    if (!sameProperties) propertyNames.clear(), properties.clear();
    std::uint32_t base = static_cast<std::uint32_t>(points.size());
    points.insert(points.end(), other.points.begin(), other.points.end());
    for (std::size_t s = 1; s < other.offsets.size(); ++s) offsets.push_back(base + other.offsets[s]);
    if (sameScalars) scalars.insert(scalars.end(), other.scalars.begin(), other.scalars.end());
    if (sameProperties) properties.insert(properties.end(), other.properties.begin(), other.properties.end());
    if (source.empty()) source = other.source;
    else source += " + " + other.source;
}

}  // namespace curette
