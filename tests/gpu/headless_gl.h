/* headless_gl.h - an OpenGL 4.5 core or OpenGL ES context with no window and no GPU required: EGL on
   Mesa's surfaceless platform (llvmpipe when there is no GPU, or when LIBGL_ALWAYS_SOFTWARE=1), with the
   GL entry points loaded through eglGetProcAddress (so one program uses desktop GL and GLES alike), and
   the few helpers the GPU programs share: compiling a program, a shader storage buffer, an R32UI
   texture of words. Offline code (C++17); throws std::runtime_error with the GL log on failure. */
#ifndef DSN_TESTS_GPU_HEADLESS_GL_H
#define DSN_TESTS_GPU_HEADLESS_GL_H

#include <GLES3/gl31.h>

#include <cstdint>
#include <string>
#include <vector>

namespace headless_gl {

enum class Api {
    gl45,   /* OpenGL 4.5 core: GLSL 4.30 compute shaders */
    gles31, /* OpenGL ES 3.1: GLSL ES 3.10 compute shaders */
    gles30  /* OpenGL ES 3.0: GLSL ES 3.00 fragment shaders (what WebGL2 has) */
};

/* The GL functions the programs use, from eglGetProcAddress. */
struct Functions {
#define HEADLESS_GL_FUNCTION(name) decltype(&::name) name = nullptr;
#include "headless_gl_functions.inc"
#undef HEADLESS_GL_FUNCTION
};

class Context {
  public:
    /* Opens a context of `api` and makes it current; throws when it cannot. */
    explicit Context(Api api);
    ~Context();
    Context(const Context &) = delete;
    Context &operator=(const Context &) = delete;

    Api api() const { return api_; }
    /* "GL_RENDERER, GL_VERSION" */
    std::string description() const;
    /* The #version line (and ES precision) that starts every shader of this API. */
    std::string shader_preamble() const;

    /* A linked program from a compute shader, or from a vertex and a fragment shader. */
    GLuint compute_program(const std::string &source) const;
    GLuint render_program(const std::string &vertex, const std::string &fragment) const;

    /* A shader storage buffer holding `bytes` bytes (copied from `data` when not null). */
    GLuint storage_buffer(const void *data, size_t bytes) const;
    /* `bytes` bytes of a buffer (mapped for reading: GLES has no glGetBufferSubData). */
    void read_buffer(GLuint buffer, void *out, size_t bytes) const;
    /* A texture of 32-bit words, 1024 per row (`components` 1: R32UI, 4: RGBA32UI), read with texelFetch
       at (index % 1024, index / 1024). */
    GLuint word_texture(const std::vector<uint32_t> &words, int components) const;

    /* Throws with `what` when GL reports an error. */
    void check(const char *what) const;

    Functions gl;

  private:
    Api api_;
    void *display_ = nullptr, *context_ = nullptr;
};

const char *api_name(Api api);

} // namespace headless_gl

#endif /* DSN_TESTS_GPU_HEADLESS_GL_H */
