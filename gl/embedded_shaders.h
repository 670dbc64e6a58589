#pragma once
// The table of shaders compiled into the binary (generated from shaders/ by cmake/embed_shaders_run.cmake).

#include <span>
#include <string_view>

namespace curette::gl {

struct EmbeddedShader {
    std::string_view name;    // path under shaders/, e.g. "raycast.comp"
    std::string_view source;
};

std::span<const EmbeddedShader> embeddedShaders();

}  // namespace curette::gl
