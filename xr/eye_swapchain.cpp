#include "xr/eye_swapchain.h"

#include "xr/xr_result.h"
#include "xr/xr_struct.h"

#include <epoxy/gl.h>
#include <epoxy/glx.h>

#define XR_USE_PLATFORM_XLIB
#define XR_USE_GRAPHICS_API_OPENGL
#include <openxr/openxr_platform.h>

#include <cstring>
#include <stdexcept>

namespace curette::xr {

std::vector<std::int64_t> preferredSwapchainFormats() { return {GL_SRGB8_ALPHA8, GL_RGBA8}; }

EyeSwapchain::EyeSwapchain(XrInstance instance, XrSession session, std::int64_t format, glm::ivec2 size) : instance_(instance), size_(size) {
    auto info = typed<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
    info.usageFlags = XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT | XR_SWAPCHAIN_USAGE_SAMPLED_BIT;
    info.format = format;
    info.sampleCount = 1;
    info.width = static_cast<std::uint32_t>(size.x);
    info.height = static_cast<std::uint32_t>(size.y);
    info.faceCount = 1;
    info.arraySize = 1;
    info.mipCount = 1;
    check(instance, xrCreateSwapchain(session, &info, &swapchain_), "xrCreateSwapchain");
    std::uint32_t count = 0;
    check(instance, xrEnumerateSwapchainImages(swapchain_, 0, &count, nullptr), "xrEnumerateSwapchainImages");
    std::vector<XrSwapchainImageOpenGLKHR> images(count, typed<XrSwapchainImageOpenGLKHR>(XR_TYPE_SWAPCHAIN_IMAGE_OPENGL_KHR));
    check(instance, xrEnumerateSwapchainImages(swapchain_, count, &count, reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())),
          "xrEnumerateSwapchainImages");
    for (const XrSwapchainImageOpenGLKHR& image : images) textures_.push_back(image.image);
}

EyeSwapchain::~EyeSwapchain() {
    if (swapchain_ != XR_NULL_HANDLE) xrDestroySwapchain(swapchain_);
}

void EyeSwapchain::fill(const std::vector<std::uint8_t>& rgba8, glm::ivec2 size) {
    if (size.x > size_.x || size.y > size_.y || rgba8.size() != static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) * 4)
        throw std::logic_error("EyeSwapchain::fill: image larger than the swapchain or of the wrong size");
    std::uint32_t index = 0;
    auto acquire = typed<XrSwapchainImageAcquireInfo>(XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO);
    check(instance_, xrAcquireSwapchainImage(swapchain_, &acquire, &index), "xrAcquireSwapchainImage");
    auto wait = typed<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
    wait.timeout = XR_INFINITE_DURATION;
    check(instance_, xrWaitSwapchainImage(swapchain_, &wait), "xrWaitSwapchainImage");
    std::vector<std::uint8_t> bottomUp(rgba8.size());
    const std::size_t row = static_cast<std::size_t>(size.x) * 4;
    for (int y = 0; y < size.y; ++y)
        std::memcpy(bottomUp.data() + static_cast<std::size_t>(size.y - 1 - y) * row, rgba8.data() + static_cast<std::size_t>(y) * row, row);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(textures_.at(index), 0, 0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    auto release = typed<XrSwapchainImageReleaseInfo>(XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO);
    check(instance_, xrReleaseSwapchainImage(swapchain_, &release), "xrReleaseSwapchainImage");
}

}  // namespace curette::xr
