#pragma once
// Move-only owners of GL objects (Magnum style): each deletes its name on destruction, so no GL object
// outlives its owner or leaks between passes. Created with DSA (glCreate*), GL 4.5.

#include <epoxy/gl.h>

#include <utility>

namespace curette::gl {

template <typename Traits>
class Object {
public:
    Object() = default;
    explicit Object(GLuint name) : name_(name) {}
    ~Object() { reset(); }
    Object(Object&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
    Object& operator=(Object&& other) noexcept {
        if (this != &other) {
            reset();
            name_ = std::exchange(other.name_, 0);
        }
        return *this;
    }
    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;

    GLuint name() const { return name_; }
    explicit operator bool() const { return name_ != 0; }
    void reset() {
        if (name_) Traits::destroy(name_);
        name_ = 0;
    }

private:
    GLuint name_ = 0;
};

struct BufferTraits { static void destroy(GLuint n) { glDeleteBuffers(1, &n); } };
struct TextureTraits { static void destroy(GLuint n) { glDeleteTextures(1, &n); } };
struct FramebufferTraits { static void destroy(GLuint n) { glDeleteFramebuffers(1, &n); } };
struct RenderbufferTraits { static void destroy(GLuint n) { glDeleteRenderbuffers(1, &n); } };
struct VertexArrayTraits { static void destroy(GLuint n) { glDeleteVertexArrays(1, &n); } };
struct ProgramTraits { static void destroy(GLuint n) { glDeleteProgram(n); } };
struct ShaderTraits { static void destroy(GLuint n) { glDeleteShader(n); } };
struct QueryTraits { static void destroy(GLuint n) { glDeleteQueries(1, &n); } };

using Buffer = Object<BufferTraits>;
using Texture = Object<TextureTraits>;
using Framebuffer = Object<FramebufferTraits>;
using Renderbuffer = Object<RenderbufferTraits>;
using VertexArray = Object<VertexArrayTraits>;
using ProgramName = Object<ProgramTraits>;
using ShaderName = Object<ShaderTraits>;
using Query = Object<QueryTraits>;

inline Buffer createBuffer() { GLuint n = 0; glCreateBuffers(1, &n); return Buffer(n); }
inline Texture createTexture(GLenum target) { GLuint n = 0; glCreateTextures(target, 1, &n); return Texture(n); }
// A 2-D texture of one level, sampled without filtering (a per-pixel buffer a pass writes and reads), labelled
// for GL debuggers.
inline Texture createPixelBuffer2D(GLenum format, int width, int height, const char* label) {
    Texture t = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(t.name(), 1, format, width, height);
    glTextureParameteri(t.name(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.name(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glObjectLabel(GL_TEXTURE, t.name(), -1, label);
    return t;
}
inline Framebuffer createFramebuffer() { GLuint n = 0; glCreateFramebuffers(1, &n); return Framebuffer(n); }
inline Renderbuffer createRenderbuffer() { GLuint n = 0; glCreateRenderbuffers(1, &n); return Renderbuffer(n); }
inline VertexArray createVertexArray() { GLuint n = 0; glCreateVertexArrays(1, &n); return VertexArray(n); }
inline Query createQuery(GLenum target) { GLuint n = 0; glCreateQueries(target, 1, &n); return Query(n); }

}  // namespace curette::gl
