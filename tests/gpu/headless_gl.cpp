// headless_gl.cpp - the EGL surfaceless context and GL helpers of headless_gl.h.
#include "headless_gl.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace headless_gl {

namespace {

[[noreturn]] void fail(const std::string &what) { throw std::runtime_error(what); }

std::string egl_error(const char *what) {
    char code[16];
    snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(eglGetError()));
    return std::string(what) + " failed (EGL error " + code + ")";
}

} // namespace

const char *api_name(Api api) {
    switch (api) {
    case Api::gl45:
        return "gl45";
    case Api::gles31:
        return "gles31";
    case Api::gles30:
        return "gles30";
    }
    return "?";
}

Context::Context(Api api) : api_(api) {
    // Only the surfaceless platform needs no window system and no device node.
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_platform_display) fail("EGL: no eglGetPlatformDisplayEXT (Mesa's EGL is needed)");
    EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) fail(egl_error("eglGetPlatformDisplayEXT(surfaceless)"));
    if (!eglInitialize(display, nullptr, nullptr)) fail(egl_error("eglInitialize"));
    display_ = display;

    const bool desktop = api == Api::gl45;
    if (!eglBindAPI(desktop ? EGL_OPENGL_API : EGL_OPENGL_ES_API)) fail(egl_error("eglBindAPI"));
    const EGLint major = desktop ? 4 : 3, minor = desktop ? 5 : api == Api::gles31 ? 1 : 0;
    std::vector<EGLint> attributes = {EGL_CONTEXT_MAJOR_VERSION, major, EGL_CONTEXT_MINOR_VERSION, minor};
    if (desktop) {
        attributes.push_back(EGL_CONTEXT_OPENGL_PROFILE_MASK);
        attributes.push_back(EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT);
    }
    attributes.push_back(EGL_NONE);
    // No config and no surface (EGL_KHR_no_config_context, EGL_KHR_surfaceless_context): nothing is shown.
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes.data());
    if (context == EGL_NO_CONTEXT) fail(egl_error("eglCreateContext"));
    context_ = context;
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) fail(egl_error("eglMakeCurrent"));

#define HEADLESS_GL_FUNCTION(name)                                                                           \
    gl.name = reinterpret_cast<decltype(gl.name)>(eglGetProcAddress(#name));                                 \
    if (!gl.name) fail("GL: no " #name);
#include "headless_gl_functions.inc"
#undef HEADLESS_GL_FUNCTION
}

Context::~Context() {
    if (display_) {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (context_) eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
}

std::string Context::description() const {
    auto text = [&](GLenum name) {
        const GLubyte *value = gl.glGetString(name);
        return value ? std::string(reinterpret_cast<const char *>(value)) : std::string("?");
    };
    return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

std::string Context::shader_preamble() const {
    switch (api_) {
    case Api::gl45:
        return "#version 430 core\n";
    case Api::gles31:
        return "#version 310 es\nprecision highp int;\nprecision highp float;\n";
    case Api::gles30:
        return "#version 300 es\nprecision highp int;\nprecision highp float;\nprecision highp usampler2D;\n";
    }
    return "";
}

void Context::check(const char *what) const {
    const GLenum error = gl.glGetError();
    if (error != GL_NO_ERROR) {
        char code[16];
        snprintf(code, sizeof code, "0x%04X", error);
        fail(std::string("GL error ") + code + " in " + what);
    }
}

namespace {

GLuint compile(const Functions &gl, GLenum stage, const std::string &source) {
    GLuint shader = gl.glCreateShader(stage);
    const char *text = source.c_str();
    gl.glShaderSource(shader, 1, &text, nullptr);
    gl.glCompileShader(shader);
    GLint ok = 0;
    gl.glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[8192] = "";
        gl.glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        gl.glDeleteShader(shader);
        fail(std::string("shader compilation failed:\n") + log);
    }
    return shader;
}

GLuint link(const Functions &gl, const std::vector<GLuint> &shaders) {
    GLuint program = gl.glCreateProgram();
    for (GLuint shader : shaders) gl.glAttachShader(program, shader);
    gl.glLinkProgram(program);
    for (GLuint shader : shaders) gl.glDeleteShader(shader);
    GLint ok = 0;
    gl.glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[8192] = "";
        gl.glGetProgramInfoLog(program, sizeof log, nullptr, log);
        gl.glDeleteProgram(program);
        fail(std::string("program link failed:\n") + log);
    }
    return program;
}

} // namespace

GLuint Context::compute_program(const std::string &source) const {
    return link(gl, {compile(gl, GL_COMPUTE_SHADER, source)});
}

GLuint Context::render_program(const std::string &vertex, const std::string &fragment) const {
    return link(gl, {compile(gl, GL_VERTEX_SHADER, vertex), compile(gl, GL_FRAGMENT_SHADER, fragment)});
}

GLuint Context::storage_buffer(const void *data, size_t bytes) const {
    GLuint buffer = 0;
    gl.glGenBuffers(1, &buffer);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    gl.glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes == 0 ? 4 : bytes), data,
                    GL_DYNAMIC_DRAW);
    check("storage_buffer");
    return buffer;
}

void Context::read_buffer(GLuint buffer, void *out, size_t bytes) const {
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    const void *mapped =
        gl.glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), GL_MAP_READ_BIT);
    if (!mapped) fail("glMapBufferRange failed");
    memcpy(out, mapped, bytes);
    gl.glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
    check("read_buffer");
}

GLuint Context::word_texture(const std::vector<uint32_t> &words, int components) const {
    const size_t row = 1024, texels = (words.size() + components - 1) / components;
    const size_t width = texels < row ? (texels == 0 ? 1 : texels) : row, height = (texels + row - 1) / row;
    std::vector<uint32_t> padded(width * (height == 0 ? 1 : height) * components, 0u);
    std::copy(words.begin(), words.end(), padded.begin());
    GLuint texture = 0;
    gl.glGenTextures(1, &texture);
    gl.glBindTexture(GL_TEXTURE_2D, texture);
    // Integer textures are complete only with nearest filtering.
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.glTexImage2D(GL_TEXTURE_2D, 0, components == 1 ? GL_R32UI : GL_RGBA32UI, static_cast<GLsizei>(width),
                    static_cast<GLsizei>(height == 0 ? 1 : height), 0,
                    components == 1 ? GL_RED_INTEGER : GL_RGBA_INTEGER, GL_UNSIGNED_INT, padded.data());
    check("word_texture");
    return texture;
}

} // namespace headless_gl
