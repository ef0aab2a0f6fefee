// All GL calls of the app. See renderer.hpp.
#include "gpu/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "gpu/shader_sources.hpp"
#include "isolux/frame.hpp"

namespace fs = std::filesystem;

namespace isolux::app {

namespace {

fs::file_time_type newest_stamp(const fs::path& dir) {
    fs::file_time_type newest{};
    std::error_code ec;
    if (dir.empty()) return newest;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        auto t = fs::last_write_time(e.path(), ec);
        if (!ec && t > newest) newest = t;
    }
    return newest;
}

void ensure_target(GpuTarget& t, int w, int h, GLenum internal_format) {
    w = std::max(1, w);
    h = std::max(1, h);
    if (t.fbo && t.w == w && t.h == h && t.internal_format == internal_format) return;
    if (!t.tex) glGenTextures(1, &t.tex);
    if (!t.fbo) glGenFramebuffers(1, &t.fbo);
    glBindTexture(GL_TEXTURE_2D, t.tex);
    const GLenum type = internal_format == GL_RGBA8 ? GL_UNSIGNED_BYTE : GL_FLOAT;
    glTexImage2D(GL_TEXTURE_2D, 0, GLint(internal_format), w, h, 0, GL_RGBA, type, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.tex, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    t.w = w;
    t.h = h;
    t.internal_format = internal_format;
}

GLuint make_texture() {
    GLuint t = 0;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    const std::uint8_t zero[4] = {0, 0, 0, 0};
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, zero);
    return t;
}

// The light texture (RGB or grey) to RGBA8 rows (GL row 0 = the texture's top row).
std::vector<std::uint8_t> to_rgba(const LightTexture& tex, Rect r) {
    std::vector<std::uint8_t> out(std::size_t(r.w) * r.h * 4);
    for (int y = 0; y < r.h; ++y)
        for (int x = 0; x < r.w; ++x) {
            std::uint8_t* d = &out[(std::size_t(y) * r.w + x) * 4];
            for (int k = 0; k < 3; ++k) d[k] = tex.value(r.x + x, r.y + y, k);
            d[3] = 255;
        }
    return out;
}

void uniform_i(GLuint p, const char* n, int v) { glUniform1i(glGetUniformLocation(p, n), v); }
void uniform_f(GLuint p, const char* n, float v) { glUniform1f(glGetUniformLocation(p, n), v); }
void uniform_2i(GLuint p, const char* n, int a, int b) { glUniform2i(glGetUniformLocation(p, n), a, b); }
void uniform_2f(GLuint p, const char* n, float a, float b) { glUniform2f(glGetUniformLocation(p, n), a, b); }

void begin_query(Renderer& r, int i) {
    if (!r.query_pending[i]) glBeginQuery(GL_TIME_ELAPSED, r.queries[i]);
}
void end_query(Renderer& r, int i) {
    if (!r.query_pending[i]) {
        glEndQuery(GL_TIME_ELAPSED);
        r.query_pending[i] = true;
    }
}
void collect_queries(Renderer& r) {
    double* out[3] = {&r.times.sprites, &r.times.blur, &r.times.composite};
    for (int i = 0; i < 3; ++i) {
        if (!r.query_pending[i]) continue;
        GLint ready = 0;
        glGetQueryObjectiv(r.queries[i], GL_QUERY_RESULT_AVAILABLE, &ready);
        if (!ready) continue;
        GLuint64 ns = 0;
        glGetQueryObjectui64v(r.queries[i], GL_QUERY_RESULT, &ns);
        *out[i] = double(ns) / 1e6;
        r.query_pending[i] = false;
    }
}

void blur_and_composite(Renderer& r, Rect view, const Params& p, const CompositeOptions& o) {
    glDisable(GL_BLEND);
    glBindVertexArray(r.vao);
    r.ran.blur = false;
    r.ran.composite = false;
    bool light_changed = false;
    if (r.light_dirty || !r.blur_valid || stages_changed(r.blur_params, p).has(Stage::blur)) {
        // The blur runs once per retrace, like core's render_frame.
        r.ran.blur = true;
        light_changed = true;
        begin_query(r, 1);
        const int w = std::max(1, r.light_rect.w), h = std::max(1, r.light_rect.h);
        ensure_target(r.blur_sums, w, h, GL_RGBA32F);
        ensure_target(r.blurred, w, h, GL_RGBA8);
        glUseProgram(r.blur.id);
        glActiveTexture(GL_TEXTURE0);
        uniform_i(r.blur.id, "u_source", 0);
        uniform_i(r.blur.id, "u_radius", p.blur_radius);
        uniform_i(r.blur.id, "u_surface", 1);
        uniform_i(r.blur.id, "u_within_surfaces", r.surface_revision != 0 && blur_within_surfaces(p) ? 1 : 0);
        uniform_2i(r.blur.id, "u_surface_origin", r.surface_rect.x - r.light_rect.x, r.surface_rect.y - r.light_rect.y);
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D, r.surface_tex);
        glActiveTexture(GL_TEXTURE0);
        // Pass 1: horizontal sums in 0..255 units, unrounded (float target).
        glBindFramebuffer(GL_FRAMEBUFFER, r.blur_sums.fbo);
        glViewport(0, 0, w, h);
        glBindTexture(GL_TEXTURE_2D, r.light_tex);
        uniform_2i(r.blur.id, "u_direction", 1, 0);
        uniform_f(r.blur.id, "u_input_scale", 255.0f);
        uniform_i(r.blur.id, "u_final_pass", 0);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        // Pass 2: vertical sums, divided once with box_blur's integer rounding.
        glBindFramebuffer(GL_FRAMEBUFFER, r.blurred.fbo);
        glBindTexture(GL_TEXTURE_2D, r.blur_sums.tex);
        uniform_2i(r.blur.id, "u_direction", 0, 1);
        uniform_f(r.blur.id, "u_input_scale", 1.0f);
        uniform_i(r.blur.id, "u_final_pass", 1);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        end_query(r, 1);
        r.light_dirty = false;
        r.blur_valid = true;
        r.blur_params = p;
    }
    const bool same = r.composite_valid && !light_changed && !r.ran.sprites && r.composite_view == view &&
                      !stages_changed(r.composite_params, p).has(Stage::composite) &&
                      r.composite_show == int(o.show_light) && r.composite_split == o.split;
    if (same) return;  // nothing the composite reads changed
    r.ran.composite = true;
    r.composite_valid = true;
    r.composite_view = view;
    r.composite_params = p;
    r.composite_show = int(o.show_light);
    r.composite_split = o.split;
    begin_query(r, 2);
    ensure_target(r.final, view.w, view.h, GL_RGBA8);
    glBindFramebuffer(GL_FRAMEBUFFER, r.final.fbo);
    glViewport(0, 0, view.w, view.h);
    glUseProgram(r.composite.id);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r.color.tex);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, r.blurred.tex);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, r.flat_tex);
    glActiveTexture(GL_TEXTURE0);
    const GLuint c = r.composite.id;
    uniform_i(c, "u_color", 0);
    uniform_i(c, "u_light", 1);
    uniform_i(c, "u_light_flat", 2);
    uniform_2i(c, "u_view_origin", view.x, view.y);
    uniform_2i(c, "u_light_origin", r.light_rect.x, r.light_rect.y);
    uniform_2i(c, "u_flat_origin", r.flat_rect.x, r.flat_rect.y);
    uniform_f(c, "u_ambient", float(p.ambient_clarity));
    uniform_i(c, "u_dark_unlit", p.dark_unlit ? 1 : 0);
    uniform_i(c, "u_shadow", p.mode == Mode::shadow ? 1 : 0);
    uniform_i(c, "u_light_mix", p.light_mix == LightMix::surface ? 1 : 0);
    uniform_f(c, "u_exposure", float(p.exposure));
    uniform_i(c, "u_tone_map", p.tone_map == ToneMap::reinhard_knee ? 1 : 0);
    uniform_i(c, "u_show", o.show_light ? 1 : 0);
    uniform_i(c, "u_split", o.split);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    end_query(r, 2);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace

bool renderer_reload_shaders(Renderer& r, bool force) {
    const fs::file_time_type stamp = newest_stamp(r.shader_dir);
    if (!force && stamp == r.shader_stamp) return false;
    r.shader_stamp = stamp;
    std::string error;
    GpuProgram* programs[4] = {&r.sprites, &r.blur, &r.composite, &r.present};
    const char* names[4][2] = {{"sprites.vert", "sprites.frag"},
                               {"fullscreen.vert", "blur.frag"},
                               {"fullscreen.vert", "composite.frag"},
                               {"present.vert", "present.frag"}};
    for (int i = 0; i < 4; ++i) {
        const GLuint id = build_program(r.shader_dir, {{GL_VERTEX_SHADER, names[i][0]}, {GL_FRAGMENT_SHADER, names[i][1]}}, error);
        if (!id) continue;  // keep the last good program
        if (programs[i]->id) glDeleteProgram(programs[i]->id);
        programs[i]->id = id;
    }
    r.shader_error = error;
    r.light_dirty = true;
    r.composite_valid = false;
    r.sprites_revision = ~0ull;
    return true;
}

bool renderer_init(Renderer& r, std::string& error) {
    r.shader_dir = shader_folder();
    renderer_reload_shaders(r, true);
    if (!r.sprites.id || !r.blur.id || !r.composite.id || !r.present.id) {
        error = "shaders did not compile: " + r.shader_error;
        return false;
    }
    glGenVertexArrays(1, &r.vao);
    glGenBuffers(1, &r.instance_vbo);
    glBindVertexArray(r.vao);
    glBindBuffer(GL_ARRAY_BUFFER, r.instance_vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 8 * sizeof(float), nullptr);
    glVertexAttribDivisor(0, 1);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 8 * sizeof(float), (void*)(4 * sizeof(float)));
    glVertexAttribDivisor(1, 1);
    glBindVertexArray(0);
    r.atlas = make_texture();
    r.light_tex = make_texture();
    r.flat_tex = make_texture();
    r.surface_tex = make_texture();
    const std::int32_t ground = -1;
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32I, 1, 1, 0, GL_RED_INTEGER, GL_INT, &ground);
    r.overlay_tex = make_texture();
    glBindTexture(GL_TEXTURE_2D, r.overlay_tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glGenQueries(3, r.queries);
    if (GLenum e = glGetError(); e != GL_NO_ERROR) {
        error = "OpenGL error " + std::to_string(e) + " while creating objects";
        return false;
    }
    return true;
}

void renderer_shutdown(Renderer& r) {
    for (GpuProgram* p : {&r.sprites, &r.blur, &r.composite, &r.present})
        if (p->id) glDeleteProgram(p->id);
    GLuint textures[] = {r.atlas, r.light_tex, r.flat_tex, r.overlay_tex, r.surface_tex};
    glDeleteTextures(5, textures);
    for (GpuTarget* t : {&r.color, &r.blur_sums, &r.blurred, &r.final}) {
        if (t->tex) glDeleteTextures(1, &t->tex);
        if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
    }
    glDeleteBuffers(1, &r.instance_vbo);
    glDeleteVertexArrays(1, &r.vao);
    glDeleteQueries(3, r.queries);
    r = Renderer{};
}

void renderer_set_atlas(Renderer& r, const Tileset& tileset);

void renderer_set_world(Renderer& r, const World& world) {
    if (r.world_revision == world.revision) return;
    r.world_revision = world.revision;
    if (r.atlas_built != world.built_revision || world.built_revision == 0) {
        r.atlas_built = world.built_revision;
        renderer_set_atlas(r, world.tileset);
    }
    std::vector<float> inst;
    const std::vector<std::uint32_t> order = draw_order(world.placed);
    inst.reserve(order.size() * 8);
    for (std::uint32_t k : order) {
        const SpriteInstance& in = world.placed.instances[k];
        const Image& im = world.tileset.sprites[std::size_t(in.sprite)].image;
        const auto& pos = r.atlas_pos[std::size_t(in.sprite)];
        const float v[8] = {float(in.x), float(in.y), float(im.width), float(im.height),
                            float(pos[0]), float(pos[1]), float(im.width), float(im.height)};
        inst.insert(inst.end(), v, v + 8);
    }
    glBindBuffer(GL_ARRAY_BUFFER, r.instance_vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(inst.size() * sizeof(float)), inst.data(), GL_STATIC_DRAW);
    r.instance_count = GLsizei(order.size());
}

void renderer_set_atlas(Renderer& r, const Tileset& tileset) {
    // Shelf-pack the sprites into one atlas.
    const auto& sprites = tileset.sprites;
    int max_w = 1;
    long area = 0;
    for (const Sprite& s : sprites) {
        max_w = std::max(max_w, s.image.width + 1);
        area += long(s.image.width + 1) * (s.image.height + 1);
    }
    GLint max_size = 4096;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    const int width = std::min<int>(max_size, std::max(max_w, int(std::sqrt(double(area)) * 1.2) + 1));
    std::vector<std::array<int, 2>> pos(sprites.size());
    int x = 0, y = 0, shelf = 0;
    for (std::size_t i = 0; i < sprites.size(); ++i) {
        const Image& im = sprites[i].image;
        if (x + im.width > width) {
            x = 0;
            y += shelf + 1;
            shelf = 0;
        }
        pos[i] = {x, y};
        x += im.width + 1;
        shelf = std::max(shelf, im.height);
    }
    const int height = y + shelf;
    std::vector<std::uint8_t> pixels(std::size_t(width) * std::max(1, height) * 4, 0);
    for (std::size_t i = 0; i < sprites.size(); ++i) {
        const Image& im = sprites[i].image;
        for (int sy = 0; sy < im.height; ++sy)
            for (int sx = 0; sx < im.width; ++sx) {
                const std::uint8_t* s = im.at(sx, sy);
                std::uint8_t* d = &pixels[(std::size_t(pos[i][1] + sy) * width + pos[i][0] + sx) * 4];
                for (int k = 0; k < 4; ++k) d[k] = s[k];  // straight: sprites.frag premultiplies in float
            }
    }
    r.atlas_w = width;
    r.atlas_h = std::max(1, height);
    glBindTexture(GL_TEXTURE_2D, r.atlas);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, r.atlas_w, r.atlas_h, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    r.atlas_pos = std::move(pos);
}

double renderer_upload_light(Renderer& r, const LightTexture& tex, Rect dirty) {
    const auto start = std::chrono::steady_clock::now();
    glBindTexture(GL_TEXTURE_2D, r.light_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (!(tex.rect == r.light_rect) || tex.rect.empty()) {
        const Rect all = tex.rect.empty() ? Rect{tex.rect.x, tex.rect.y, 0, 0} : tex.rect;
        std::vector<std::uint8_t> px = all.empty() ? std::vector<std::uint8_t>(4, 0) : to_rgba(tex, all);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, std::max(1, all.w), std::max(1, all.h), 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, px.data());
        r.light_rect = tex.rect;
    } else {
        // Only the part that changed.
        const Rect d = intersect(dirty, tex.rect);
        if (!d.empty()) {
            std::vector<std::uint8_t> px = to_rgba(tex, d);
            glTexSubImage2D(GL_TEXTURE_2D, 0, d.x - tex.rect.x, d.y - tex.rect.y, d.w, d.h, GL_RGBA,
                            GL_UNSIGNED_BYTE, px.data());
        }
    }
    r.light_dirty = true;
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    r.times.upload = ms;
    return ms;
}

void renderer_upload_surface_ids(Renderer& r, const SurfaceIds& ids, std::uint64_t revision) {
    if (ids.id.empty()) revision = 0;
    if (revision == r.surface_revision) return;
    r.surface_revision = revision;
    r.light_dirty = true;  // blurred within other surfaces, or none
    if (!revision) return;
    r.surface_rect = ids.rect;
    glBindTexture(GL_TEXTURE_2D, r.surface_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32I, std::max(1, ids.rect.w), std::max(1, ids.rect.h), 0, GL_RED_INTEGER, GL_INT,
                 ids.id.data());
}

void renderer_upload_flat_light(Renderer& r, const LightTexture& tex) {
    r.composite_valid = false;
    glBindTexture(GL_TEXTURE_2D, r.flat_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    std::vector<std::uint8_t> px = tex.rect.empty() ? std::vector<std::uint8_t>(4, 0) : to_rgba(tex, tex.rect);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, std::max(1, tex.rect.w), std::max(1, tex.rect.h), 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, px.data());
    r.flat_rect = tex.rect;
}

void renderer_upload_overlay(Renderer& r, const Image& overlay, Rect rect) {
    glBindTexture(GL_TEXTURE_2D, r.overlay_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    const std::uint8_t zero[4] = {0, 0, 0, 0};
    const bool empty = overlay.width <= 0 || overlay.height <= 0;
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, empty ? 1 : overlay.width, empty ? 1 : overlay.height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, empty ? zero : overlay.rgba.data());
    r.overlay_rect = empty ? Rect{} : rect;
}

void renderer_draw(Renderer& r, Rect view, const Params& p, const CompositeOptions& o) {
    collect_queries(r);
    r.ran.sprites = !(r.sprites_view == view) || r.sprites_revision != r.world_revision;
    if (!r.ran.sprites) return blur_and_composite(r, view, p, o);
    r.sprites_view = view;
    r.sprites_revision = r.world_revision;
    begin_query(r, 0);
    ensure_target(r.color, view.w, view.h, GL_RGBA16F);
    glBindFramebuffer(GL_FRAMEBUFFER, r.color.fbo);
    glViewport(0, 0, view.w, view.h);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(r.sprites.id);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r.atlas);
    uniform_i(r.sprites.id, "u_atlas", 0);
    glUniform4f(glGetUniformLocation(r.sprites.id, "u_view"), float(view.x), float(view.y), float(view.w),
                float(view.h));
    uniform_2f(r.sprites.id, "u_atlas_size", float(r.atlas_w), float(r.atlas_h));
    glBindVertexArray(r.vao);
    glDrawArraysInstanced(GL_TRIANGLES, 0, 6, r.instance_count);
    end_query(r, 0);
    blur_and_composite(r, view, p, o);
}

void renderer_draw_with_colour(Renderer& r, const Image& colour, Rect view, const Params& p,
                               const CompositeOptions& o) {
    r.ran.sprites = true;  // the colour target is replaced: the composite must run
    r.sprites_revision = ~0ull;
    ensure_target(r.color, view.w, view.h, GL_RGBA16F);
    std::vector<float> px(std::size_t(view.w) * view.h * 4);
    for (std::size_t i = 0; i < std::size_t(view.w) * view.h; ++i) {
        const float a = colour.rgba[i * 4 + 3] / 255.0f;
        for (int k = 0; k < 3; ++k) px[i * 4 + k] = colour.rgba[i * 4 + k] / 255.0f * a;
        px[i * 4 + 3] = a;
    }
    glBindTexture(GL_TEXTURE_2D, r.color.tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, view.w, view.h, 0, GL_RGBA, GL_FLOAT, px.data());
    r.color.internal_format = GL_RGBA32F;
    blur_and_composite(r, view, p, o);
}

void renderer_present(Renderer& r, int ww, int wh, double x, double y, double zoom, Rect view) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, ww, wh);
    glClearColor(0.08f, 0.09f, 0.11f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_BLEND);
    const GLuint p = r.present.id;
    glUseProgram(p);
    const double x0 = x / ww * 2 - 1, x1 = (x + view.w * zoom) / ww * 2 - 1;
    const double y0 = 1 - (y + view.h * zoom) / wh * 2, y1 = 1 - y / wh * 2;
    glUniform4f(glGetUniformLocation(p, "u_rect"), float(x0), float(y0), float(x1), float(y1));
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r.final.tex);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, r.overlay_tex);
    glActiveTexture(GL_TEXTURE0);
    uniform_i(p, "u_final", 0);
    uniform_i(p, "u_overlay", 1);
    uniform_2f(p, "u_view_origin", float(view.x), float(view.y));
    uniform_2f(p, "u_view_size", float(view.w), float(view.h));
    uniform_2f(p, "u_overlay_origin", float(r.overlay_rect.x), float(r.overlay_rect.y));
    uniform_2f(p, "u_overlay_size", float(std::max(1, r.overlay_rect.w)), float(std::max(1, r.overlay_rect.h)));
    uniform_f(p, "u_overlay_opacity", r.overlay_rect.empty() ? 0.0f : 1.0f);
    glUniform3f(glGetUniformLocation(p, "u_background"), 0.08f, 0.09f, 0.11f);
    glBindVertexArray(r.vao);
    glDrawArrays(GL_TRIANGLES, 0, 6);
}

namespace {
Image read_target(const GpuTarget& t) {
    Image out(t.w, t.h);
    glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, t.w, t.h, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return out;
}
}  // namespace

Image renderer_read_final(Renderer& r) { return read_target(r.final); }
Image renderer_read_blurred(Renderer& r) { return read_target(r.blurred); }

Image renderer_read_window(int width, int height) {
    Image out(width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
    // GL's first row is the window's bottom one.
    for (int y = 0; y < height / 2; ++y)
        std::swap_ranges(out.at(0, y), out.at(0, y) + std::size_t(width) * 4, out.at(0, height - 1 - y));
    for (std::size_t i = 3; i < out.rgba.size(); i += 4) out.rgba[i] = 255;
    return out;
}

}  // namespace isolux::app
