#pragma once
// What each binding unit of shaders/bindings.glsl holds, as a resource of the frame plan's table
// (render/model/gpu_resources.h): the resources a pass's programs really bind, found by the GL's introspection,
// are held against the pass's declared reads and writes (Renderer::setAuditBindings, tests/render/test_frame_plan.cpp).

#include "gl/program.h"
#include "render/model/frame_plan.h"

#include <set>
#include <string>
#include <vector>

namespace curette {

struct BoundResources {
    Pass pass = Pass::Count;
    std::set<Resource> resources;
    std::vector<std::string> unknown;   // units no resource stands for (and no pass keeps to itself), by name
};

// A program that ran in `pass`: its active bindings as resources. A pass's own constants and scratch (step IV's
// anti-aliasing offsets, the compositor's Poisson disk, the ray cast's tile spans and sample counter) are no
// resource of the table: no other pass reads them, so no declaration orders them.
void addResourcesBound(BoundResources& out, const gl::ProgramBindings& bindings);

}  // namespace curette
