#include "render/model/frame.h"

#include "render/model/frame_plan.h"

namespace curette {

bool slabPassRuns(ShadingMode shading, bool tubesInView) {
    PlanInputs in;
    in.shading = shading;
    in.tubes = in.tubesInView = tubesInView;
    return planFrame(in).runs(Pass::SlabPass);
}

glm::dvec3 worldLightDirection(const Light& l, const OrbitCamera& camera) {
    glm::dvec3 d = l.cameraSpace ? l.direction.x * camera.right() + l.direction.y * camera.up() - l.direction.z * camera.forward()
                                 : l.direction;
    return glm::normalize(d);
}

}  // namespace curette
