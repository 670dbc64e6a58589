// Headless contexts on the two EGL platforms (gl/context.h): which targets each --gpu choice tries, on made-up
// device lists, and, on this machine's Mesa (which lists its software renderer as an EGL device too), the
// same frame rendered through the device platform and through the surfaceless one, pixel for pixel.
#include "base/error.h"
#include "render/renderer.h"
#include "tests/render/gl_test_support.h"

#include <gtest/gtest.h>

#include <cstring>

namespace curette {
namespace {

using gl::GpuChoice;
using gl::HeadlessPlatform;
using gl::HeadlessTarget;

gl::EglDevice device(int index, bool software, std::string problem = {}) {
    gl::EglDevice d;
    d.index = index;
    d.software = software;
    d.extensions = software ? "EGL_MESA_device_software" : "EGL_EXT_device_drm";
    d.eglVendor = software ? "Mesa Project" : "NVIDIA";
    d.eglVersion = "1.5";
    d.problem = std::move(problem);
    return d;
}

gl::EglPlatforms platforms(bool surfaceless, std::vector<gl::EglDevice> devices) {
    gl::EglPlatforms p;
    p.surfaceless = surfaceless;
    p.deviceEnumeration = p.platformDevice = true;
    p.devices = std::move(devices);
    return p;
}

const HeadlessTarget kSurfaceless{HeadlessPlatform::Surfaceless, -1};
HeadlessTarget onDevice(int i) { return {HeadlessPlatform::Device, i}; }

TEST(HeadlessContext, AutomaticTriesTheFirstHardwareDeviceThenSurfacelessThenSoftware) {
    // Mesa with a GPU: the GPU's device first (surfaceless would pick it too, but maybe another one).
    EXPECT_EQ(gl::headlessTargets(platforms(true, {device(0, true), device(1, false), device(2, false)}), {}),
              (std::vector<HeadlessTarget>{onDevice(1), kSurfaceless, onDevice(0)}));
    // This machine: Mesa, no GPU: surfaceless, as before the device platform, then the software device.
    EXPECT_EQ(gl::headlessTargets(platforms(true, {device(0, true)}), {}), (std::vector<HeadlessTarget>{kSurfaceless, onDevice(0)}));
    // NVIDIA's driver alone: no surfaceless platform.
    EXPECT_EQ(gl::headlessTargets(platforms(false, {device(0, false)}), {}), (std::vector<HeadlessTarget>{onDevice(0)}));
    // A device whose display cannot be initialised is not tried.
    EXPECT_EQ(gl::headlessTargets(platforms(true, {device(0, false, "eglInitialize failed"), device(1, true)}), {}),
              (std::vector<HeadlessTarget>{kSurfaceless, onDevice(1)}));
    EXPECT_THROW(gl::headlessTargets(platforms(false, {}), {}), SystemError);
}

TEST(HeadlessContext, AnExplicitChoiceTriesOnlyItsOwnTarget) {
    gl::EglPlatforms p = platforms(true, {device(0, false), device(1, true)});
    EXPECT_EQ(gl::headlessTargets(p, {GpuChoice::Kind::Device, 0}), std::vector<HeadlessTarget>{onDevice(0)});
    EXPECT_EQ(gl::headlessTargets(p, {GpuChoice::Kind::Device, 1}), std::vector<HeadlessTarget>{onDevice(1)});
    EXPECT_EQ(gl::headlessTargets(p, {GpuChoice::Kind::Software, -1}), std::vector<HeadlessTarget>{onDevice(1)});
    EXPECT_EQ(gl::headlessTargets(p, {GpuChoice::Kind::Surfaceless, -1}), std::vector<HeadlessTarget>{kSurfaceless});
    // Without a software device, llvmpipe means surfaceless (whose renderer is checked when the context exists).
    EXPECT_EQ(gl::headlessTargets(platforms(true, {device(0, false)}), {GpuChoice::Kind::Software, -1}),
              std::vector<HeadlessTarget>{kSurfaceless});
    try {
        gl::headlessTargets(p, {GpuChoice::Kind::Device, 2});
        ADD_FAILURE() << "device 2 of 2 accepted";
    } catch (const SystemError& e) {
        EXPECT_NE(std::string(e.what()).find("0: hardware, NVIDIA"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("1: software, Mesa Project"), std::string::npos) << e.what();
    }
    EXPECT_THROW(gl::headlessTargets(platforms(false, {device(0, false)}), {GpuChoice::Kind::Surfaceless, -1}), SystemError);
    EXPECT_THROW(gl::headlessTargets(platforms(false, {device(0, false)}), {GpuChoice::Kind::Software, -1}), SystemError);
}

// A small lit scene, rendered on whatever context is current.
Image renderSmallScene(gl::Context& context) {
    glm::ivec3 dims(32);
    VolumeData volume = test::makeVolume(dims, test::centredAffine(dims), ScalarType::UInt8, test::blobField);
    TransferFunction tf = test::rampTransferFunction(40, 200, 0.6);
    Renderer renderer(context, volume, tf);
    FrameDescription frame;
    frame.camera.fit(glm::dvec3(0.0), 28.0);
    frame.camera.azimuthDeg = 30;
    frame.camera.elevationDeg = 20;
    frame.size = {64, 64};
    frame.shading = ShadingMode::Phong;
    renderer.render(frame);
    return renderer.readImage();
}

TEST(HeadlessContext, TheDevicePlatformRendersTheSamePixelsAsSurfaceless) {
    gl::EglPlatforms found = gl::queryEglPlatforms();
    if (!found.surfaceless || found.devices.empty()) GTEST_SKIP() << "needs both platforms; " << found.describeDevices();
    const gl::EglDevice* software = nullptr;
    for (const gl::EglDevice& d : found.devices)
        if (d.software && d.problem.empty()) software = &d;
    if (!software) GTEST_SKIP() << "the device platform lists no software device to compare with surfaceless llvmpipe";

    Image viaSurfaceless, viaDevice;
    {
        auto context = gl::createHeadlessContext({GpuChoice::Kind::Surfaceless, -1});
        EXPECT_NE(context->info().platform.find("surfaceless"), std::string::npos) << context->info().platform;
        viaSurfaceless = renderSmallScene(*context);
    }
    {
        auto context = gl::createHeadlessContext({GpuChoice::Kind::Device, software->index});
        EXPECT_EQ(context->info().platform, "EGL device " + std::to_string(software->index) + " (EGL_EXT_platform_device)");
        EXPECT_TRUE(context->info().softwareRenderer) << context->info().renderer;
        viaDevice = renderSmallScene(*context);
    }
    ASSERT_EQ(viaSurfaceless.pixels.size(), viaDevice.pixels.size());
    int covered = 0;
    for (const glm::vec4& p : viaSurfaceless.pixels) covered += p.a > 0.1f;
    EXPECT_GT(covered, 200) << "the scene must show something to compare";
    EXPECT_EQ(std::memcmp(viaSurfaceless.pixels.data(), viaDevice.pixels.data(), viaDevice.pixels.size() * sizeof(glm::vec4)), 0)
        << "the device platform's llvmpipe renders other pixels than the surfaceless platform's";
}

}  // namespace
}  // namespace curette
