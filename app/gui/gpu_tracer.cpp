// See gpu_tracer.hpp.
#include "gui/gpu_tracer.hpp"

#include <algorithm>
#include <cstdlib>

#include "gui/shader_sources.hpp"

namespace isolux::app {

namespace {

bool has_compute() {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    return major > 4 || (major == 4 && minor >= 3);
}

GLuint r8ui_texture(int w, int h, const void* data) {
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8UI, w, h, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, data);
    return tex;
}

void replace_texture(GLuint& tex, int w, int h, const void* data) {
    if (tex) glDeleteTextures(1, &tex);
    tex = r8ui_texture(w, h, data);
}

}  // namespace

bool gpu_tracer_init(GpuTracer& t, std::string& error) {
    if (!has_compute()) {
        error = "no compute shaders (OpenGL 4.3) in this context";
        return false;
    }
    t.program = build_program(shader_folder(), {{GL_COMPUTE_SHADER, "trace.comp"}}, error);
    if (!t.program) return false;
    glGenBuffers(1, &t.targets);
    glGenBuffers(1, &t.falloff);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &t.max_texture);
    const GLubyte* name = glGetString(GL_RENDERER);
    t.renderer = name ? reinterpret_cast<const char*>(name) : "";
    return true;
}

void gpu_tracer_free(GpuTracer& t) {
    if (t.program) glDeleteProgram(t.program);
    for (GLuint* tex : {&t.obstacles, &t.lit, &t.reached})
        if (*tex) glDeleteTextures(1, tex);
    for (GLuint* buf : {&t.targets, &t.falloff})
        if (*buf) glDeleteBuffers(1, buf);
    t = GpuTracer{};
}

bool gpu_tracer_is_software(const GpuTracer& t) {
    for (const char* soft : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
        if (t.renderer.find(soft) != std::string::npos) return true;
    return false;
}

bool gpu_trace(GpuTracer& t, const Mask& obstacles, std::uint64_t obstacles_revision,
               const std::vector<LightMask*>& masks, const Params& p) {
    if (!t.program || p.rays_over_obstacles || p.occluders != Occluders::footprints) return false;  // the CPU traces these
    while (glGetError() != GL_NO_ERROR) {
    }  // earlier errors are not ours
    if (obstacles.width > t.max_texture || obstacles.height > t.max_texture) return false;
    for (const LightMask* m : masks)
        if (std::llabs(m->cx) >= 1000000000 || std::llabs(m->cy) >= 1000000000 || m->clip.w > t.max_texture ||
            m->clip.h > t.max_texture)
            return false;
    // The obstacle map, uploaded when it changed (a 1x1 empty one for none).
    if (t.obstacles_revision != obstacles_revision || !t.obstacles) {
        static const std::uint8_t none = 0;
        const bool empty = obstacles.bits.empty();
        replace_texture(t.obstacles, empty ? 1 : obstacles.width, empty ? 1 : obstacles.height,
                        empty ? &none : obstacles.bits.data());
        t.obstacles_rect = empty ? Rect{0, 0, 0, 0} : obstacles.rect();
        t.obstacles_revision = obstacles_revision;
    }
    glUseProgram(t.program);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, t.obstacles);
    glUniform1i(glGetUniformLocation(t.program, "obstacles"), 0);
    glUniform2i(glGetUniformLocation(t.program, "obstacle_origin"), t.obstacles_rect.x, t.obstacles_rect.y);
    glUniform2i(glGetUniformLocation(t.program, "obstacle_size"), t.obstacles_rect.w, t.obstacles_rect.h);
    glUniform1i(glGetUniformLocation(t.program, "mode"), p.mode == Mode::light ? 0 : p.mode == Mode::shadow ? 1 : 2);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    std::vector<GLint> targets;
    std::vector<GLuint> table;
    for (LightMask* m : masks) {
        if (m->clip.empty()) continue;
        // The rays' targets as offsets from the centre, in trace_light's order.
        targets.clear();
        for_each_ray_target(m->cx, m->cy, m->a, m->b, p, [&](std::int64_t x, std::int64_t y) {
            targets.push_back(GLint(x - m->cx));
            targets.push_back(GLint(y - m->cy));
        });
        table.resize(std::size_t(std::max(m->a, m->b)) + 1);
        for (std::size_t d = 0; d < table.size(); ++d) table[d] = falloff(std::int64_t(d), p.falloff_scale);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, t.targets);
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(targets.size() * sizeof(GLint)), targets.data(), GL_STREAM_DRAW);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, t.targets);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, t.falloff);
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(table.size() * sizeof(GLuint)), table.data(), GL_STREAM_DRAW);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, t.falloff);
        // Output images the clip's size, cleared to 0 (unlit, unreached).
        if (t.lit_w != m->clip.w || t.lit_h != m->clip.h || !t.lit) {
            replace_texture(t.lit, m->clip.w, m->clip.h, nullptr);
            replace_texture(t.reached, m->clip.w, m->clip.h, nullptr);
            t.lit_w = m->clip.w;
            t.lit_h = m->clip.h;
        }
        const GLubyte zero = 0;
        glClearTexImage(t.lit, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
        glClearTexImage(t.reached, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, t.obstacles);  // (creating the outputs bound them here)
        glBindImageTexture(0, t.lit, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
        glBindImageTexture(1, t.reached, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
        glUniform2i(glGetUniformLocation(t.program, "centre"), GLint(m->cx), GLint(m->cy));
        glUniform4i(glGetUniformLocation(t.program, "clip"), m->clip.x, m->clip.y, m->clip.w, m->clip.h);
        const GLint rays = GLint(targets.size() / 2);
        glUniform1i(glGetUniformLocation(t.program, "ray_count"), rays);
        glDispatchCompute(GLuint((rays + 63) / 64), 1, 1);
        glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
        glBindTexture(GL_TEXTURE_2D, t.lit);
        glGetTexImage(GL_TEXTURE_2D, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, m->value.data());
        if (p.mode == Mode::shadow) {
            glBindTexture(GL_TEXTURE_2D, t.reached);
            glGetTexImage(GL_TEXTURE_2D, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, m->reached.data());
        }
    }
    glUseProgram(0);
    return glGetError() == GL_NO_ERROR;
}

}  // namespace isolux::app
