#pragma once
// An OpenXR structure zeroed with its type set (the API reads `type` and `next` of every structure it is
// handed; aggregate initialisation with the type alone leaves the compiler asking for every other member).

#include <openxr/openxr.h>

namespace curette::xr {

template <typename T>
T typed(XrStructureType type) {
    T value{};
    value.type = type;
    return value;
}

}  // namespace curette::xr
