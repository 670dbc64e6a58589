#pragma once
// The renderer of one scene: it owns the GPU resources the scene needs (allocated once, only those its
// shading modes use) and runs the frame's passes. See DESIGN.md "One frame, as data flows".

#include "render/frame.h"
#include "render/gl/context.h"
#include "render/gl/program.h"
#include "render/gl/timer.h"
#include "render/gpu_volume.h"
#include "render/image.h"
#include "render/transfer_function_texture.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace curette {

struct GpuAllocation {
    std::string name;    // e.g. "V (data volume)"
    std::string format;  // e.g. "R8"
    std::size_t bytes = 0;
};

class Renderer {
public:
    Renderer(gl::Context& context, const VolumeData& volume, const TransferFunction& tf);
    ~Renderer();

    void setTransferFunction(const TransferFunction& tf);
    const VolumeGeometry& geometry() const { return volume_.geometry(); }
    double resolveStepMm(const RaycastSettings& settings) const;

    // Runs the frame on the GPU; the result stays in outputTexture() until read.
    void render(const FrameDescription& frame);
    GLuint outputTexture() const { return output_.name(); }
    glm::ivec2 outputSize() const { return outputSize_; }
    Image readImage() const;

    // Count the volume samples the ray caster takes (for `bench`; slows the frame slightly when on).
    void setCountSamples(bool on) { countSamples_ = on; }
    std::uint64_t samplesLastFrame() const;

    // GPU time per pass of the frames rendered since the last call (milliseconds).
    std::vector<std::pair<std::string, double>> collectTimings() { return timers_.collectMilliseconds(); }
    std::vector<GpuAllocation> gpuAllocations() const;

private:
    gl::Program& raycastProgram(ShadingMode mode);
    void updateOccupancy();
    void ensureOutput(glm::ivec2 size);

    gl::Context& context_;
    GpuVolume volume_;
    std::unique_ptr<TransferFunctionTexture> tf_;
    gl::Texture occupancy_;
    gl::Texture output_;
    glm::ivec2 outputSize_{0};
    gl::Buffer sampleCounter_;
    bool countSamples_ = false;
    std::map<std::pair<ShadingMode, bool>, gl::Program> raycastPrograms_;
    gl::TimerSet timers_;
};

}  // namespace curette
