#include "render/lighting.h"

#include <algorithm>

namespace curette {

void setLightingUniforms(gl::Program& p, const FrameDescription& frame, const TransferFunction::Material& m) {
    int count = std::min<int>(static_cast<int>(frame.lights.size()), kMaxLights);
    glm::vec3 directions[kMaxLights], colors[kMaxLights];
    for (int i = 0; i < count; ++i) {
        const Light& l = frame.lights[static_cast<std::size_t>(i)];
        directions[i] = glm::vec3(worldLightDirection(l, frame.camera));
        colors[i] = glm::vec3(l.color);
    }
    p.set("lightCount", count);
    if (count > 0) {
        glProgramUniform3fv(p.name(), p.location("lightDirection"), count, &directions[0].x);
        glProgramUniform3fv(p.name(), p.location("lightColor"), count, &colors[0].x);
    }
    p.set("material", glm::vec4(glm::dvec4(m.ambient, m.diffuse, m.specular, m.specularPower)));
}

}  // namespace curette
