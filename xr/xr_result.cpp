#include "xr/xr_result.h"

#include "base/error.h"

namespace curette::xr {

std::string resultName(XrInstance instance, XrResult result) {
    char name[XR_MAX_RESULT_STRING_SIZE] = {};
    if (instance != XR_NULL_HANDLE && XR_SUCCEEDED(xrResultToString(instance, result, name))) return name;
    return "XrResult " + std::to_string(static_cast<int>(result));
}

XrResult check(XrInstance instance, XrResult result, const char* call) {
    if (XR_FAILED(result)) throw SystemError(std::string("OpenXR ") + call + ": " + resultName(instance, result));
    return result;
}

}  // namespace curette::xr
