#pragma once
// One eye's OpenXR swapchain (XR_KHR_opengl_enable: its images are GL textures): acquired, filled with the
// eye's 8-bit image and released once a frame.

#include <openxr/openxr.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace curette::xr {

// The formats curette writes its 8-bit display values into, best first: GL_SRGB8_ALPHA8 (the values are
// sRGB-encoded, so a compositor reading it as sRGB shows them as a monitor does), then GL_RGBA8.
std::vector<std::int64_t> preferredSwapchainFormats();

class EyeSwapchain {
public:
    EyeSwapchain(XrInstance instance, XrSession session, std::int64_t format, glm::ivec2 size);
    ~EyeSwapchain();
    EyeSwapchain(const EyeSwapchain&) = delete;
    EyeSwapchain& operator=(const EyeSwapchain&) = delete;

    // Acquires an image, waits for it, copies `rgba8` (rows top-down, `size` <= the swapchain's) into its
    // lower-left corner as GL lays rows out (bottom-up), and releases it.
    void fill(const std::vector<std::uint8_t>& rgba8, glm::ivec2 size);

    XrSwapchain handle() const { return swapchain_; }
    glm::ivec2 size() const { return size_; }

private:
    XrInstance instance_;
    XrSwapchain swapchain_ = XR_NULL_HANDLE;
    glm::ivec2 size_;
    std::vector<std::uint32_t> textures_;
};

}  // namespace curette::xr
