#include "render/image_texture.h"

namespace curette {

void ImageTexture::update(const Image& image) {
    glm::ivec2 size(image.width, image.height);
    if (size.x <= 0 || size.y <= 0) return;
    if (!texture_ || size != size_) {
        texture_ = gl::createTexture(GL_TEXTURE_2D);
        glTextureStorage2D(texture_.name(), 1, GL_RGBA8, size.x, size.y);
        glTextureParameteri(texture_.name(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(texture_.name(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(texture_.name(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(texture_.name(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glObjectLabel(GL_TEXTURE, texture_.name(), -1, "panel image");
        size_ = size;
    }
    std::vector<std::uint8_t> rgba = toRgba8(image, glm::vec4(0, 0, 0, 1));
    glTextureSubImage2D(texture_.name(), 0, 0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
}

}  // namespace curette
