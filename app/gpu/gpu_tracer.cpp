// See gpu_tracer.hpp.
#include "gpu/gpu_tracer.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "gpu/shader_sources.hpp"

namespace isolux::app {

namespace {

// One storage buffer's bytes, `data` null for none (a buffer is never empty).
void buffer_data(GLuint buf, std::size_t bytes, const void* data, GLenum usage) {
    static const std::uint32_t none[2] = {0, 0};
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buf);
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes ? bytes : sizeof none), bytes ? data : none, usage);
}

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
        t.lit_w = m.clip.w;
        t.lit_h = m.clip.h;
    }
    const GLubyte zero = 0;
    glClearTexImage(t.lit, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
    glClearTexImage(t.reached, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
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
    t.start_program = build_program(shader_folder(), {{GL_COMPUTE_SHADER, "start_layers.comp"}}, error);
    if (!t.start_program) return false;
    for (GLuint* buf : {&t.targets, &t.falloff, &t.spans, &t.overflow, &t.shown_start, &t.shown, &t.surface_height,
                        &t.surface_sprite, &t.lights, &t.ray_targets})
        glGenBuffers(1, buf);
    for (GLuint buf : {t.surface_height, t.surface_sprite}) buffer_data(buf, 0, nullptr, GL_STATIC_DRAW);  // none yet
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &t.max_layers);
    {
        GLint major = 0, minor = 0;
        glGetIntegerv(GL_MAJOR_VERSION, &major);
        glGetIntegerv(GL_MINOR_VERSION, &minor);
        t.get_sub_image = major > 4 || (major == 4 && minor >= 5);
    }
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &t.max_texture);
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &t.max_storage);
    const GLubyte* name = glGetString(GL_RENDERER);
    t.renderer = name ? reinterpret_cast<const char*>(name) : "";
    return true;
}

void gpu_tracer_free(GpuTracer& t) {
    for (GLuint prog : {t.program, t.solids_program, t.points_program, t.start_program})
        if (prog) glDeleteProgram(prog);
    for (GLuint* tex : {&t.obstacles, &t.lit, &t.reached, &t.layers})
        if (*tex) glDeleteTextures(1, tex);
    for (GLuint* buf : {&t.targets, &t.falloff, &t.spans, &t.overflow, &t.shown_start, &t.shown, &t.surface_height,
                        &t.surface_sprite, &t.lights, &t.ray_targets})
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
// pixel and its surface) into storage buffers, uploaded when the map
// changed. False when they are larger than a storage buffer takes.
bool upload_occluders(GpuTracer& t, const OccluderMap& occ, std::uint64_t revision, bool points) {
    const std::size_t pixels = occ.spans.size();
    const std::uint64_t most = std::uint64_t(std::max(t.max_storage, 0));
    if (std::uint64_t(std::max<std::size_t>(pixels, 1)) * 4 * sizeof(float) > most) return false;
    const Surface& surface = occ.surface;
    if (points && (std::uint64_t(occ.shown_start.size()) * sizeof(std::uint32_t) > most ||
                   std::uint64_t(occ.shown.size()) * sizeof(OccluderMap::Shown) > most ||
                   std::uint64_t(surface.height.size()) * sizeof(float) > most))
        return false;
    if (t.spans_revision != revision) {  // one empty pixel for none
        std::vector<float> spans(std::max<std::size_t>(pixels, 1) * 4, 0.f);
        for (std::size_t i = 0; i < pixels; ++i) {
            const Spans& s = occ.spans[i];
            spans[4 * i] = s.lower.low, spans[4 * i + 1] = s.lower.high;
            spans[4 * i + 2] = s.upper.low, spans[4 * i + 3] = s.upper.high;
        }
        buffer_data(t.spans, spans.size() * sizeof(float), spans.data(), GL_STATIC_DRAW);
        t.spans_rect = pixels ? occ.rect : Rect{0, 0, 0, 0};
        t.spans_revision = revision;
    }
    if (points && t.shown_revision != revision) {
        static_assert(sizeof(OccluderMap::Shown) == 8, "the shader's Shown: a float and a uint");
        const bool empty = occ.shown_start.size() < 2;  // no pixel: no points
        buffer_data(t.shown_start, empty ? 0 : occ.shown_start.size() * sizeof(std::uint32_t), occ.shown_start.data(),
                    GL_STATIC_DRAW);
        buffer_data(t.shown, occ.shown.size() * sizeof(OccluderMap::Shown), occ.shown.data(), GL_STATIC_DRAW);
        t.shown_revision = revision;
    }
    if (points && t.surface_revision != revision) {
        // Which pixels show an overlay, a bit each; and their heights.
        const std::size_t n = surface.instance.size();
        std::vector<std::uint32_t> sprite(n / 32 + 1, 0);
        for (std::size_t i = 0; i < n; ++i)
            if (surface.instance[i] >= 0) sprite[i >> 5] |= 1u << (i & 31);
        buffer_data(t.surface_sprite, sprite.size() * sizeof(std::uint32_t), sprite.data(), GL_STATIC_DRAW);
        buffer_data(t.surface_height, surface.height.size() * sizeof(float), surface.height.data(), GL_STATIC_DRAW);
        t.surface_rect = n ? surface.rect : Rect{0, 0, 0, 0};
        t.surface_revision = revision;
    }
    return true;
}

// A light as the shaders read it (their `Light`, std430).
struct GpuLight {
    GLint centre[2], extent[2], ground_rays[2], sprite_rays[2];
    GLint clip[4], area[4];
    double height;
    GLint layer, unused = 0;
};
static_assert(sizeof(GpuLight) == 80, "the shaders' Light: 80 bytes");

// An r8ui array texture of at least w x h x count (start_layers.comp
// starts each light's layer: a clear would take the calling thread).
void ready_layers(GpuTracer& t, int w, int h, int count) {
    if (w <= t.layers_w && h <= t.layers_h && count <= t.layer_count && t.layers) return;
    t.layers_w = std::max(w, t.layers_w), t.layers_h = std::max(h, t.layers_h);
    t.layer_count = std::max(count, t.layer_count);
    if (t.layers) glDeleteTextures(1, &t.layers);
    glGenTextures(1, &t.layers);
    glBindTexture(GL_TEXTURE_2D_ARRAY, t.layers);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R8UI, t.layers_w, t.layers_h, t.layer_count, 0, GL_RED_INTEGER,
                 GL_UNSIGNED_BYTE, nullptr);
}

void set_map_uniforms(GLuint program, const GpuTracer& t, bool surface = false) {
    glUniform2i(glGetUniformLocation(program, "span_origin"), t.spans_rect.x, t.spans_rect.y);
    glUniform2i(glGetUniformLocation(program, "span_size"), t.spans_rect.w, t.spans_rect.h);
    if (!surface) return;
    glUniform2i(glGetUniformLocation(program, "surface_origin"), t.surface_rect.x, t.surface_rect.y);
    glUniform2i(glGetUniformLocation(program, "surface_size"), t.surface_rect.w, t.surface_rect.h);
}

// Every ray target of lights of half-extents `keys` (a, b) in
// t.ray_targets, each extent's run of offsets from the centre (in the CPU
// tracers' order) in t.rays.run. Kept across frames: uploaded again only
// when an extent is new or the rays changed (at most 64 extents kept
// besides the frame's own). `keys` holds each extent once.
void ray_runs(GpuTracer& t, const std::vector<RayRuns::Key>& keys, const Params& p) {
    RayRuns& r = t.rays;
    const bool same_rays = r.rays == p.rays && r.skip == p.ray_skip;
    bool all = same_rays;
    for (const RayRuns::Key& k : keys) all = all && r.run.count(k);
    if (all) return;
    if (!same_rays || r.run.size() + keys.size() > 64) r.run.clear(), r.targets.clear();
    r.rays = p.rays, r.skip = p.ray_skip;
    for (const RayRuns::Key& k : keys) {
        if (r.run.count(k)) continue;
        const GLint first = GLint(r.targets.size() / 2);
        for_each_ray_target(0, 0, k[0], k[1], p, [&](std::int64_t x, std::int64_t y) {
            r.targets.push_back(GLint(x));
            r.targets.push_back(GLint(y));
        });
        r.run[k] = {first, GLint(r.targets.size() / 2) - first};
    }
    buffer_data(t.ray_targets, r.targets.size() * sizeof(GLint), r.targets.data(), GL_STATIC_DRAW);
}

// One batch of lights: each light's layer started, then the ground pass and
// the sprite pass, each one dispatch for all of them, and every layer read
// back at once. False when a ray held more live shades than the ground pass
// does.
bool trace_batch(GpuTracer& t, const OccluderMap& occ, const std::vector<LightMask*>& masks,
                 const std::vector<double>& heights, const Params& p, bool sprite_points) {
    const int count = int(masks.size());
    // The lights' records, with their rays' runs (ray_runs), and one falloff
    // table for all.
    std::vector<GpuLight> lights(masks.size());
    int w = 1, h = 1, most_ground = 0, most_sprite = 0, reach = 0;
    std::vector<RayRuns::Key> keys;
    for (const LightMask* m : masks) {
        keys.push_back({m->a, m->b});
        if (sprite_points) keys.push_back({m->a, m->b + occ.tallest});
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    ray_runs(t, keys, p);
    for (int k = 0; k < count; ++k) {
        const LightMask& m = *masks[std::size_t(k)];
        GpuLight& l = lights[std::size_t(k)];
        const Rect area = intersect(Rect{int(m.cx) - m.a, int(m.cy) - m.b, 2 * m.a + 1, 2 * m.b + 1}, m.clip);
        l.centre[0] = GLint(m.cx), l.centre[1] = GLint(m.cy), l.extent[0] = m.a, l.extent[1] = m.b;
        l.clip[0] = m.clip.x, l.clip[1] = m.clip.y, l.clip[2] = m.clip.w, l.clip[3] = m.clip.h;
        l.area[0] = area.x, l.area[1] = area.y, l.area[2] = area.w, l.area[3] = area.h;
        l.height = std::max(heights[std::size_t(k)], 0.0);
        l.layer = k;
        const auto ground = t.rays.run.at({m.a, m.b});
        l.ground_rays[0] = ground[0], l.ground_rays[1] = ground[1];
        most_ground = std::max(most_ground, int(ground[1]));
        l.sprite_rays[0] = l.sprite_rays[1] = 0;
        if (sprite_points) {
            const auto sprite = t.rays.run.at({m.a, m.b + occ.tallest});
            l.sprite_rays[0] = sprite[0], l.sprite_rays[1] = sprite[1];
            most_sprite = std::max(most_sprite, int(sprite[1]));
        }
        w = std::max(w, m.clip.w), h = std::max(h, m.clip.h), reach = std::max({reach, m.a, m.b});
    }
    std::vector<GLuint> table(std::size_t(reach) + 1);
    for (std::size_t d = 0; d < table.size(); ++d) table[d] = falloff(std::int64_t(d), p.falloff_scale);
    buffer_data(t.falloff, table.size() * sizeof(GLuint), table.data(), GL_STREAM_DRAW);
    buffer_data(t.lights, lights.size() * sizeof(GpuLight), lights.data(), GL_STREAM_DRAW);
    const GLuint no = 0;
    buffer_data(t.overflow, sizeof no, &no, GL_STREAM_READ);
    ready_layers(t, w, h, count);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, t.falloff);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, t.spans);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, t.overflow);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, t.lights);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, t.surface_height);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, t.surface_sprite);
    glBindImageTexture(0, t.layers, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R8UI);

    // Each layer started: unlit, but the sprite pixels no ray walks.
    glUseProgram(t.start_program);
    set_map_uniforms(t.start_program, t, true);
    glUniform1i(glGetUniformLocation(t.start_program, "tallest"), occ.tallest);
    glUniform1i(glGetUniformLocation(t.start_program, "sprite_points"), sprite_points ? 1 : 0);
    glDispatchCompute(GLuint((w + 7) / 8), GLuint((h + 7) / 8), GLuint(count));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    // The ground pass: every light's rays (the area's sprite pixels left to the sprite pass).
    glUseProgram(t.solids_program);
    set_map_uniforms(t.solids_program, t, true);
    glUniform1i(glGetUniformLocation(t.solids_program, "skip_sprites"), sprite_points ? 1 : 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, t.ray_targets);
    glDispatchCompute(GLuint((most_ground + 63) / 64), GLuint(count), 1);
    if (sprite_points) {
        // The sprite pass: the points its rays light.
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glUseProgram(t.points_program);
        set_map_uniforms(t.points_program, t);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, t.shown_start);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, t.shown);
        glDispatchCompute(GLuint((most_sprite + 63) / 64), GLuint(count), 1);
    }
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint overflowed = 0;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, t.overflow);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(GLuint), &overflowed);
    if (overflowed) return false;
    // One read-back of the batch's layers (of all of them before GL 4.5),
    // each mask's clip copied out of its own.
    thread_local std::vector<std::uint8_t> all;
    const bool part = t.get_sub_image;
    const int row = part ? w : t.layers_w;
    const std::size_t layer_bytes = std::size_t(row) * std::size_t(part ? h : t.layers_h);
    all.resize(layer_bytes * std::size_t(part ? count : t.layer_count));
    if (part) {
        glGetTextureSubImage(t.layers, 0, 0, 0, 0, w, h, count, GL_RED_INTEGER, GL_UNSIGNED_BYTE, GLsizei(all.size()),
                             all.data());
    } else {
        glBindTexture(GL_TEXTURE_2D_ARRAY, t.layers);
        glGetTexImage(GL_TEXTURE_2D_ARRAY, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, all.data());
    }
    for (int k = 0; k < count; ++k) {
        LightMask& m = *masks[std::size_t(k)];
        const std::uint8_t* layer = all.data() + layer_bytes * std::size_t(k);
        for (int y = 0; y < m.clip.h; ++y)
            std::memcpy(&m.value[std::size_t(y) * std::size_t(m.clip.w)], layer + std::size_t(y) * std::size_t(row),
                        std::size_t(m.clip.w));
        // Shadow mode reaches every pixel of the area, as the CPU's.
        if (p.mode == Mode::shadow) std::fill(m.reached.begin(), m.reached.end(), std::uint8_t(1));
    }
    return true;
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
    // Batches of lights in order: at most max_layers, and 64 MiB of layers.
    constexpr std::uint64_t batch_bytes = std::uint64_t(64) << 20;
    std::vector<LightMask*> batch;
    std::vector<double> batch_heights;
    int w = 0, h = 0;
    auto flush = [&] {
        const bool ok = batch.empty() || trace_batch(t, occ, batch, batch_heights, p, sprite_points);
        batch.clear(), batch_heights.clear(), w = h = 0;
        return ok;
    };
    for (std::size_t k = 0; k < masks.size(); ++k) {
        LightMask& m = *masks[k];
        if (m.clip.empty()) continue;
        const int nw = std::max(w, m.clip.w), nh = std::max(h, m.clip.h);
        if (!batch.empty() && (int(batch.size()) >= std::max(t.max_layers, 1) ||
                               std::uint64_t(nw) * std::uint64_t(nh) * (batch.size() + 1) > batch_bytes))
            if (!flush()) return glUseProgram(0), false;
        w = std::max(w, m.clip.w), h = std::max(h, m.clip.h);
        batch.push_back(&m);
        batch_heights.push_back(heights[k]);
    }
    const bool ok = flush();
    glUseProgram(0);
    return ok && glGetError() == GL_NO_ERROR;
}

std::string_view gpu_trace_frame(GpuTracer& t, const Mask& obstacles, std::uint64_t obstacles_revision,
                                 const OccluderMap* occluders, const std::vector<LightMask*>& masks,
                                 const std::vector<double>& heights, const Params& p, bool sprite_points) {
    const bool traced = occluders ? gpu_trace_solids(t, *occluders, obstacles_revision, masks, heights, p, sprite_points)
                                  : gpu_trace(t, obstacles, obstacles_revision, masks, p);
    return traced ? std::string_view("gpu") : std::string_view();
}

}  // namespace isolux::app
