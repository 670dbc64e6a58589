#pragma once
// OpenXR results as curette errors: a failed call throws SystemError naming the call and the result.

#include <openxr/openxr.h>

#include <string>

namespace curette::xr {

// The result's name (XR_ERROR_...), from the runtime when it can say, else its number.
std::string resultName(XrInstance instance, XrResult result);

// Throws SystemError("OpenXR <call>: <result>") when `result` is a failure; returns it otherwise.
XrResult check(XrInstance instance, XrResult result, const char* call);

}  // namespace curette::xr
