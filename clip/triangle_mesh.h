#pragma once
// Minimal definition until the clip-meshes branch (primitives, glTF, validation) merges its full version.
#include <glm/glm.hpp>
#include <string>
#include <vector>
namespace curette::clip {
struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;
    std::string source;
};
}  // namespace curette::clip
