#include "render/lighting.h"

#include <algorithm>
#include <string>

namespace curette {

int shadedLightCount(const FrameDescription& frame) { return std::min<int>(static_cast<int>(frame.lights.size()), kMaxLights); }

void addLightingDefines(gl::Defines& defines, const FrameDescription& frame) {
    defines.emplace_back("LIGHT_COUNT", std::to_string(shadedLightCount(frame)));
}

void setLightingUniforms(gl::Program& p, const FrameDescription& frame, const TransferFunction::Material& m) {
    int count = shadedLightCount(frame);
    glm::vec3 directions[kMaxLights], colors[kMaxLights];
    for (int i = 0; i < count; ++i) {
        const Light& l = frame.lights[static_cast<std::size_t>(i)];
        directions[i] = glm::vec3(worldLightDirection(l, frame.camera));
        colors[i] = glm::vec3(l.color);
    }
    if (count > 0) {
        glProgramUniform3fv(p.name(), p.location("lightDirection"), count, &directions[0].x);
        glProgramUniform3fv(p.name(), p.location("lightColor"), count, &colors[0].x);
    }
    p.set("material", glm::vec4(glm::dvec4(m.ambient, m.diffuse, m.specular, m.specularPower)));
}

}  // namespace curette
