// See gpu_tracer.hpp.
#include "gpu/gpu_tracer.hpp"

#include <algorithm>
#include <cstdlib>

#include "gpu/shader_sources.hpp"

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

// The rays' targets as offsets from the centre, in the CPU tracers' order,
// and the falloff by distance, into storage buffers 0 and 1 (`targets` and
// `table` are scratch, kept by the caller across a frame's lights). The rays
// run to the border of the light's area grown by `grow` rows up and down
// (the sprite pass's). Returns the number of rays.
GLint upload_rays(GpuTracer& t, const LightMask& m, const Params& p, std::vector<GLint>& targets,
                  std::vector<GLuint>& table, int grow = 0) {
    targets.clear();
    for_each_ray_target(m.cx, m.cy, m.a, m.b + grow, p, [&](std::int64_t x, std::int64_t y) {
        targets.push_back(GLint(x - m.cx));
        targets.push_back(GLint(y - m.cy));
    });
    table.resize(std::size_t(std::max(m.a, m.b)) + 1);
    for (std::size_t d = 0; d < table.size(); ++d) table[d] = falloff(std::int64_t(d), p.falloff_scale);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, t.targets);
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(targets.size() * sizeof(GLint)), targets.data(), GL_STREAM_DRAW);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, t.targets);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, t.falloff);
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(table.size() * sizeof(GLuint)), table.data(), GL_STREAM_DRAW);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, t.falloff);
    return GLint(targets.size() / 2);
}

// Output images the clip's size, cleared to 0 (unlit, unreached).
void ready_outputs(GpuTracer& t, const LightMask& m) {
    if (t.lit_w != m.clip.w || t.lit_h != m.clip.h || !t.lit) {
        replace_texture(t.lit, m.clip.w, m.clip.h, nullptr);
        replace_texture(t.reached, m.clip.w, m.clip.h, nullptr);
        replace_texture(t.points, m.clip.w, m.clip.h, nullptr);
        t.lit_w = m.clip.w;
        t.lit_h = m.clip.h;
    }
    const GLubyte zero = 0;
    glClearTexImage(t.lit, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
    glClearTexImage(t.reached, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
    glClearTexImage(t.points, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
}

// Whether the frame's masks fit what the shaders take: int centres, clips
// within the largest texture.
bool masks_fit(const GpuTracer& t, const std::vector<LightMask*>& masks) {
    for (const LightMask* m : masks)
        if (std::llabs(m->cx) >= 1000000000 || std::llabs(m->cy) >= 1000000000 || m->clip.w > t.max_texture ||
            m->clip.h > t.max_texture)
            return false;
    return true;
}

}  // namespace

bool gpu_tracer_init(GpuTracer& t, std::string& error) {
    if (!has_compute()) {
        error = "no compute shaders (OpenGL 4.3) in this context";
        return false;
    }
    t.program = build_program(shader_folder(), {{GL_COMPUTE_SHADER, "trace.comp"}}, error);
    if (!t.program) return false;
    t.solids_program = build_program(shader_folder(), {{GL_COMPUTE_SHADER, "trace_solids.comp"}}, error);
    if (!t.solids_program) return false;
    t.points_program = build_program(shader_folder(), {{GL_COMPUTE_SHADER, "sprite_points.comp"}}, error);
    if (!t.points_program) return false;
    for (GLuint* buf : {&t.targets, &t.falloff, &t.spans, &t.overflow, &t.shown_start, &t.shown}) glGenBuffers(1, buf);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &t.max_texture);
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &t.max_storage);
    const GLubyte* name = glGetString(GL_RENDERER);
    t.renderer = name ? reinterpret_cast<const char*>(name) : "";
    return true;
}

void gpu_tracer_free(GpuTracer& t) {
    for (GLuint prog : {t.program, t.solids_program, t.points_program})
        if (prog) glDeleteProgram(prog);
    for (GLuint* tex : {&t.obstacles, &t.lit, &t.reached, &t.points})
        if (*tex) glDeleteTextures(1, tex);
    for (GLuint* buf : {&t.targets, &t.falloff, &t.spans, &t.overflow, &t.shown_start, &t.shown})
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
    if (obstacles.width > t.max_texture || obstacles.height > t.max_texture || !masks_fit(t, masks)) return false;
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
        const GLint rays = upload_rays(t, *m, p, targets, table);
        ready_outputs(t, *m);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, t.obstacles);  // (creating the outputs bound them here)
        glBindImageTexture(0, t.lit, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
        glBindImageTexture(1, t.reached, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
        glUniform2i(glGetUniformLocation(t.program, "centre"), GLint(m->cx), GLint(m->cy));
        glUniform4i(glGetUniformLocation(t.program, "clip"), m->clip.x, m->clip.y, m->clip.w, m->clip.h);
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

namespace {

// The occluder map's spans (and for the sprite pass its points by ground
// pixel) into storage buffers 2, 4 and 5, uploaded when the map changed.
// False when they are larger than a storage buffer takes.
bool upload_occluders(GpuTracer& t, const OccluderMap& occ, std::uint64_t revision, bool points) {
    const std::size_t pixels = occ.spans.size();
    const std::uint64_t most = std::uint64_t(std::max(t.max_storage, 0));
    if (std::uint64_t(std::max<std::size_t>(pixels, 1)) * 4 * sizeof(float) > most) return false;
    if (points && (std::uint64_t(occ.shown_start.size()) * sizeof(std::uint32_t) > most ||
                   std::uint64_t(occ.shown.size()) * sizeof(OccluderMap::Shown) > most))
        return false;
    if (t.spans_revision != revision) {  // one empty pixel for none
        std::vector<float> spans(std::max<std::size_t>(pixels, 1) * 4, 0.f);
        for (std::size_t i = 0; i < pixels; ++i) {
            const Spans& s = occ.spans[i];
            spans[4 * i] = s.lower.low, spans[4 * i + 1] = s.lower.high;
            spans[4 * i + 2] = s.upper.low, spans[4 * i + 3] = s.upper.high;
        }
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, t.spans);
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(spans.size() * sizeof(float)), spans.data(), GL_STATIC_DRAW);
        t.spans_rect = pixels ? occ.rect : Rect{0, 0, 0, 0};
        t.spans_revision = revision;
    }
    if (points && t.shown_revision != revision) {
        static_assert(sizeof(OccluderMap::Shown) == 8, "the shader's Shown: a float and a uint");
        const std::uint32_t none[2] = {0, 0};  // no pixel: no points (a buffer is never empty)
        const bool empty = occ.shown_start.size() < 2;
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, t.shown_start);
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(empty ? sizeof none : occ.shown_start.size() * sizeof(std::uint32_t)),
                     empty ? none : occ.shown_start.data(), GL_STATIC_DRAW);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, t.shown);
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(occ.shown.empty() ? sizeof none : occ.shown.size() * sizeof(OccluderMap::Shown)),
                     occ.shown.empty() ? static_cast<const void*>(none) : occ.shown.data(), GL_STATIC_DRAW);
        t.shown_revision = revision;
    }
    return true;
}

// The ground pass of one light into m.value; false when a ray held more
// live shades than the shader does.
bool ground_pass(GpuTracer& t, LightMask& m, double height, const Params& p, std::vector<GLint>& targets,
                 std::vector<GLuint>& table) {
    glUseProgram(t.solids_program);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, t.spans);
    glUniform2i(glGetUniformLocation(t.solids_program, "span_origin"), t.spans_rect.x, t.spans_rect.y);
    glUniform2i(glGetUniformLocation(t.solids_program, "span_size"), t.spans_rect.w, t.spans_rect.h);
    const GLint rays = upload_rays(t, m, p, targets, table);
    ready_outputs(t, m);
    const GLuint no = 0;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, t.overflow);
    glBufferData(GL_SHADER_STORAGE_BUFFER, sizeof(GLuint), &no, GL_STREAM_READ);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, t.overflow);
    glBindImageTexture(0, t.lit, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
    glUniform2i(glGetUniformLocation(t.solids_program, "centre"), GLint(m.cx), GLint(m.cy));
    glUniform4i(glGetUniformLocation(t.solids_program, "clip"), m.clip.x, m.clip.y, m.clip.w, m.clip.h);
    glUniform1i(glGetUniformLocation(t.solids_program, "ray_count"), rays);
    glUniform1d(glGetUniformLocation(t.solids_program, "light_height"), std::max(height, 0.0));
    glDispatchCompute(GLuint((rays + 63) / 64), 1, 1);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint overflowed = 0;
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(GLuint), &overflowed);
    glBindTexture(GL_TEXTURE_2D, t.lit);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, m.value.data());
    // Shadow mode reaches every pixel of the area, as the CPU's.
    if (p.mode == Mode::shadow) std::fill(m.reached.begin(), m.reached.end(), std::uint8_t(1));
    return overflowed == 0;
}

// The sprite pass of one light over its ground pass: start_sprite_points on
// the CPU, then the rays of the light's area grown by the tallest point's
// rows on the GPU, into `points` (the clip's size, cleared), which light
// the sprite pixels they reach.
void sprite_pass(GpuTracer& t, LightMask& m, const OccluderMap& occ, double height, const Params& p,
                 std::vector<GLint>& targets, std::vector<GLuint>& table, std::vector<std::uint8_t>& lit) {
    start_sprite_points(m, occ, height, p);
    glUseProgram(t.points_program);
    const GLint rays = upload_rays(t, m, p, targets, table, occ.tallest);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, t.spans);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, t.shown_start);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, t.shown);
    glBindImageTexture(0, t.points, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
    const Rect area = intersect(Rect{int(m.cx) - m.a, int(m.cy) - m.b, 2 * m.a + 1, 2 * m.b + 1}, m.clip);
    glUniform2i(glGetUniformLocation(t.points_program, "span_origin"), t.spans_rect.x, t.spans_rect.y);
    glUniform2i(glGetUniformLocation(t.points_program, "span_size"), t.spans_rect.w, t.spans_rect.h);
    glUniform2i(glGetUniformLocation(t.points_program, "centre"), GLint(m.cx), GLint(m.cy));
    glUniform4i(glGetUniformLocation(t.points_program, "clip"), m.clip.x, m.clip.y, m.clip.w, m.clip.h);
    glUniform4i(glGetUniformLocation(t.points_program, "area"), area.x, area.y, area.w, area.h);
    glUniform1i(glGetUniformLocation(t.points_program, "ray_count"), rays);
    glUniform1d(glGetUniformLocation(t.points_program, "light_height"), std::max(height, 0.0));
    glDispatchCompute(GLuint((rays + 63) / 64), 1, 1);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    lit.resize(m.value.size());
    glBindTexture(GL_TEXTURE_2D, t.points);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, lit.data());
    for (std::size_t i = 0; i < lit.size(); ++i)  // only sprite pixels are written
        if (lit[i]) m.value[i] = lit[i];
}

}  // namespace

bool gpu_trace_solids(GpuTracer& t, const OccluderMap& occ, std::uint64_t occluders_revision,
                      const std::vector<LightMask*>& masks, const std::vector<double>& heights, const Params& p,
                      bool sprite_points) {
    if (!t.solids_program || p.mode == Mode::flat || heights.size() != masks.size() || !masks_fit(t, masks)) return false;
    while (glGetError() != GL_NO_ERROR) {
    }  // earlier errors are not ours
    if (!upload_occluders(t, occ, occluders_revision, sprite_points)) return false;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    std::vector<GLint> targets;
    std::vector<GLuint> table;
    std::vector<std::uint8_t> points;
    for (std::size_t k = 0; k < masks.size(); ++k) {
        LightMask& m = *masks[k];
        if (m.clip.empty()) continue;
        if (!ground_pass(t, m, heights[k], p, targets, table)) {
            glUseProgram(0);
            return false;
        }
        if (sprite_points) sprite_pass(t, m, occ, heights[k], p, targets, table, points);
    }
    glUseProgram(0);
    return glGetError() == GL_NO_ERROR;
}

std::string_view gpu_trace_frame(GpuTracer& t, const Mask& obstacles, std::uint64_t obstacles_revision,
                                 const OccluderMap* occluders, const std::vector<LightMask*>& masks,
                                 const std::vector<double>& heights, const Params& p, bool sprite_points) {
    const bool traced = occluders ? gpu_trace_solids(t, *occluders, obstacles_revision, masks, heights, p, sprite_points)
                                  : gpu_trace(t, obstacles, obstacles_revision, masks, p);
    return traced ? std::string_view("gpu") : std::string_view();
}

}  // namespace isolux::app
