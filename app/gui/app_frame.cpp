// The app's frame: app_frame.hpp.
#include "gui/app_frame.hpp"

#include "gui/app.hpp"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <new>
#include <string>
#include <cmath>
#include <thread>

#include "isolux/error.hpp"
#include "isolux/truth.hpp"

namespace isolux::app {

// The tracer the setting asks for (config.hpp: Settings::tracer): the GPU's
// compute shader for "gpu", and for "auto" when the driver is not a software
// rasteriser; the CPU otherwise, or when the GPU one is not available.
bool gpu_tracer_chosen(const App& app) {
    const std::string& want = app.tracer_override.empty() ? app.editor.settings.tracer : app.tracer_override;
    if (!app.gpu_tracer.program || want == "cpu") return false;
    return want == "gpu" || !gpu_tracer_is_software(app.gpu_tracer);
}

namespace {

LightTracer chosen_tracer(App& app) {
    if (!gpu_tracer_chosen(app)) return {};
    return [&app](const Mask& obstacles, std::uint64_t revision, const OccluderMap* occluders,
                  const std::vector<LightMask*>& masks, const std::vector<double>& heights, const Params& p,
                  bool sprite_points) {
        return gpu_trace_frame(app.gpu_tracer, obstacles, revision, occluders, masks, heights, p, sprite_points);
    };
}

// The 3D reference over the view (truth.hpp), kept while the scene's
// parameters, lights, view and world are the same. Null (and the status
// says why) when it cannot be made, e.g. a tileset without shapes.
const LightTexture* update_truth(App& app, const Scene& scene) {
    TruthCache& t = app.truth;
    const Editor& e = app.editor;
    if (t.valid && t.params == scene.params && t.lights == scene.lights && t.view == app.view &&
        t.revision == e.world.revision)
        return &t.texture;
    try {
        // Made on the frame's thread: beyond the budget the overlay is refused
        // with its estimate rather than freezing the window for minutes.
        const double work = reference_work(e.world, scene, app.view, Reference::three_d);
        if (work > huge_trace_steps) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.2g", work);
            throw Error("the 3D reference of this view would take about " + std::string(buf) +
                        " ray steps (minutes or more): use a smaller view, area or fewer lights");
        }
        t.texture = reference_texture(e.world, scene, app.view, Reference::three_d);
    } catch (const Error& err) {
        set_status(app.editor, err.what(), true);
        app.editor.overlays.truth_light = app.editor.overlays.truth_difference = false;
        app.editor.overlays.split_with_3d = false;
        t.valid = false;
        return nullptr;
    }
    t.valid = true;
    t.params = scene.params;
    t.lights = scene.lights;
    t.view = app.view;
    t.revision = e.world.revision;
    app.split_texture_holds = 0;  // upload it again
    return &t.texture;
}

// The CLI's budget in the app: a frame whose tracing is estimated beyond
// huge_trace_steps is not traced until the user says so (the prompt in
// dialogs.cpp: trace it, or undo the change). A script undoes the change and
// says why; a screenshot run stops with the CLI's message and exit code 2.
bool work_allowed(App& app, const Scene& scene, bool screenshot_mode) {
    HugeWork& h = app.huge;
    const double steps = trace_work(scene, app.view);
    if (steps <= huge_trace_steps) return true;
    if (h.approved && h.approved_params == scene.params && scene.lights.size() <= h.approved_lights) return true;
    if (h.declined && h.declined_params == scene.params) return false;
    char text[200];
    std::snprintf(text, sizeof text, "this frame would trace about %.2g ray steps (minutes or more)", steps);
    if (screenshot_mode) {
        std::cerr << "isolux: " << text << ": use a smaller area, border rays or fewer lights (isolux-cli has --allow-huge)\n";
        app.exit_code = 2;
        app.quit = true;
        return false;
    }
    if (app.script && h.script_answer != "undo") {  // as if "Trace it" were pressed
        h.approved = true;
        h.approved_params = scene.params;
        h.approved_lights = scene.lights.size();
        return true;
    }
    if (app.script) {
        undo(app.editor, app.now);
        set_status(app.editor, std::string(text) + ": the change was undone", true);
        std::cerr << "isolux: " << text << ": the change was undone\n";
        return false;
    }
    h.asking = true;
    h.steps = steps;
    return false;
}

// Approved long work (work_allowed): render_frame on a worker thread with
// the CPU tracer, which Cancel can stop. Returns true with the frame's report
// once it is done; false while it runs (the main loop then draws only its
// progress) and when it was cancelled or failed (the last frame stays, and
// these parameters are not traced again until they change). A frame that
// reuses its cached trace ends at once: the first moments are waited for
// here, so such frames never show the progress.
bool run_long_trace(App& app, const Scene& scene, const Camera& cam, FrameReport& rep) {
    LongTrace& job = app.long_trace;
    Editor& e = app.editor;
    if (!job.worker.joinable()) {
        job.cancel = false;
        job.finished = false;
        job.done = 0;
        job.total = trace_work(scene, app.view);
        job.started = app.now;
        job.cancelled = false;
        job.error.clear();
        e.frame.options.tracer = {};  // the CPU's, which checks for Cancel
        e.frame.options.control = TraceControl{&job.cancel, &job.done};
        job.worker = std::thread([&app, scene, cam, frame = e.frame_number] {
            LongTrace& j = app.long_trace;
            const auto t0 = std::chrono::steady_clock::now();
            try {
                j.report = render_frame(app.editor.frame, app.editor.world, scene, cam, frame);
            } catch (const Cancelled&) {
                j.cancelled = true;
            } catch (const Error& err) {
                j.error = err.what();
            } catch (const std::bad_alloc&) {
                j.error = "out of memory tracing this frame: use a smaller area or fewer lights";
            }
            j.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            j.finished = true;
        });
        for (int ms = 0; ms < 200 && !job.finished; ++ms) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    if (!job.finished) return false;
    job.worker.join();
    e.frame.options.control = {};
    const double seconds = job.seconds;
    char text[200];
    if (job.cancelled || !job.error.empty()) {
        HugeWork& h = app.huge;
        h.approved = false;
        h.declined = true;
        h.declined_params = scene.params;
        if (job.cancelled)
            std::snprintf(text, sizeof text, "long work cancelled at %.0f%% after %.1f s: the last frame stays until the parameters change",
                          100 * std::min(1.0, double(job.done) / std::max(1.0, job.total)), seconds);
        set_status(e, job.cancelled ? text : job.error, true);
        std::cerr << "isolux: " << (job.cancelled ? text : job.error) << "\n";
        return false;
    }
    if (job.report.lights_traced > 0)
        std::cout << "isolux: long work done: " << job.report.lights_traced << " lights traced in " << std::fixed << std::setprecision(2) << seconds << std::defaultfloat << " s\n";
    rep = job.report;
    return true;
}

// A screenshot's view is the scene's camera: as in isolux-cli, at most
// max_render_pixels, and no side beyond what the GPU's textures hold.
bool screenshot_view_fits(App& app) {
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    const Rect v = app.view;
    if ((long long)v.w * v.h <= max_render_pixels && v.w <= max_side && v.h <= max_side) return true;
    const std::string scene = !app.scene_arg.empty()                ? app.scene_arg
                              : !app.editor.scene_path.empty() ? app.editor.scene_path.string()
                                                               : std::string("the scene");
    std::cerr << "isolux: " << scene << ": camera: shows " << v.w << "x" << v.h << " pixels, over the 256-megapixel limit or "
              << "this GPU's " << max_side << "-pixel texture side: set a smaller camera, or render parts with "
              << "isolux-cli --view X,Y,W,H\n";
    app.exit_code = 2;
    app.quit = true;
    return false;
}

// An endless world's window kept around the view (follow_view). A new
// window is a new frame of reference: what was cached over the old one is
// made again. A view the editor refuses (zoomed out too far) returns to the
// last zoom that fitted.
void follow_endless_view(App& app, bool screenshot_mode) {
    Editor& e = app.editor;
    // A stroke, a slider's or a light's drag and a box select keep what they
    // started from (tiles, the document before, world pixels) in one frame:
    // the window waits for them to end.
    const ViewportState& vp = app.ui.viewport;
    if (e.stroke.active || app.ui.editing || vp.dragging_light >= 0 || vp.box_selecting) return;
    auto view_of = [&] {
        if (screenshot_mode) {
            const WorldRect& v = e.endless.last_view;
            return Rect{int(std::floor(e.view.x)), int(std::floor(e.view.y)), e.view.width > 0 ? e.view.width : v.w,
                        e.view.height > 0 ? e.view.height : v.h};
        }
        return Rect{int(std::floor(e.view.x)), int(std::floor(e.view.y)), int(std::ceil(app.window_w / e.view.zoom)) + 1,
                    int(std::ceil(app.window_h / e.view.zoom)) + 1};
    };
    Follow f = follow_view(e, view_of());
    if (f == Follow::refused && app.endless_zoom > 0 && app.endless_zoom != e.view.zoom) {
        const double cx = e.view.x + app.window_w / 2.0 / e.view.zoom, cy = e.view.y + app.window_h / 2.0 / e.view.zoom;
        e.view.zoom = app.endless_zoom;
        e.view.x = cx - app.window_w / 2.0 / e.view.zoom;
        e.view.y = cy - app.window_h / 2.0 / e.view.zoom;
        f = follow_view(e, view_of());
    }
    if (f != Follow::refused) app.endless_zoom = e.view.zoom;
    if (f != Follow::moved) return;
    app.overlay_dirty = true;
    app.truth.valid = false;
    app.split_texture_holds = 0;
    app.flat_frame = FrameState{e.frame.options};
    app.accuracy.heatmap_stale = true;
}

}  // namespace

// One frame's figures: the stages that ran, their times, the lighting
// pipeline's time (`frame_ms`) and the whole loop's (`dt`, seconds).
void push_stats(App& app, const FrameReport& rep, double frame_ms, double dt) {
    Stats& s = app.stats;
    for (int k = 0; k < stage_count; ++k) s.ms[k][s.head] = float(rep.ms[k]);
    const GpuTimes& g = app.renderer.times;
    const Renderer::Ran& ran = app.renderer.ran;
    s.ms[stage_count + 0][s.head] = rep.retraced ? float(g.upload) : 0.0f;
    s.ms[stage_count + 1][s.head] = ran.sprites ? float(g.sprites) : 0.0f;
    s.ms[stage_count + 2][s.head] = ran.blur ? float(g.blur) : 0.0f;
    s.ms[stage_count + 3][s.head] = ran.composite ? float(g.composite) : 0.0f;
    s.gpu_ran = {rep.retraced, ran.sprites, ran.blur, ran.composite};
    s.head = (s.head + 1) % Stats::frames;
    ++s.recorded;
    s.last_ran = rep.ran;
    s.lights_traced = rep.lights_traced;
    if (!rep.tracer.empty()) s.tracer = std::string(rep.tracer);
    if (!rep.rebuilt.empty()) s.last_rebuilt = rep.rebuilt;
    s.frame_ms = s.frame_ms * 0.9f + float(frame_ms) * 0.1f;
    if (dt > 0) s.loop_ms = s.loop_ms > 0 ? s.loop_ms * 0.9f + float(dt * 1000) * 0.1f : float(dt * 1000);
}

// Stops a long trace the window is closing on (its work is thrown away).
void stop_long_trace(App& app) {
    LongTrace& job = app.long_trace;
    if (!job.worker.joinable()) return;
    job.cancel = true;
    job.worker.join();
    app.editor.frame.options.control = {};
}

// A frame core refused (a tileset without the shapes `occluders` asks for,
// memory): the change that asked for it is undone with the reason in the
// status bar, and the frame state starts afresh, since the refused frame
// may have left it half made. A screenshot run stops with exit code 2.
static FrameReport refuse_frame(App& app, const std::string& why, bool screenshot_mode) {
    Editor& e = app.editor;
    fresh_frame(e);
    app.split_texture_holds = 0;
    if (screenshot_mode) {
        std::cerr << "isolux: " << why << "\n";
        app.exit_code = 2;
        app.quit = true;
        return FrameReport{};
    }
    if (!e.undo_stack.empty() && undo(e, app.now)) {
        set_status(e, why + ": the change was undone", true);
        std::cerr << "isolux: " << why << ": the change was undone\n";
    } else {
        set_status(e, why, true);
    }
    return FrameReport{};
}

// One frame of the pipeline: core traces (CPU), the renderer does the rest.
FrameReport render_app_frame(App& app, bool screenshot_mode) {
    Editor& e = app.editor;
    if (e.scene.endless) follow_endless_view(app, screenshot_mode);
    renderer_set_world(app.renderer, e.world);
    const Scene scene = render_scene(e);
    Camera cam;
    if (screenshot_mode && e.scene.endless) {
        const WorldRect& v = e.endless.last_view;
        cam = {e.view.x, e.view.y, v.w, v.h};
        app.view = camera_view(cam, e.world);
        app.view_x = app.view_y = 0;
    } else if (screenshot_mode) {
        cam = scene_to_save(e).camera;  // width 0: the whole map, as isolux-cli renders it
        app.view = camera_view(cam, e.world);
        app.view_x = app.view_y = 0;
    } else {
        const double vw = std::ceil(app.window_w / e.view.zoom) + 1, vh = std::ceil(app.window_h / e.view.zoom) + 1;
        cam = {e.view.x, e.view.y, int(vw), int(vh)};
        app.view = camera_view(cam, e.world);
        app.view_x = (app.view.x - e.view.x) * e.view.zoom;
        app.view_y = (app.view.y - e.view.y) * e.view.zoom;
    }
    if (screenshot_mode && !screenshot_view_fits(app)) return FrameReport{};
    if (!work_allowed(app, scene, screenshot_mode)) return FrameReport{};  // the last frame stays
    e.frame.options.tracer = chosen_tracer(app);
    FrameReport rep;
    if (app.long_trace.worker.joinable() || trace_work(scene, app.view) > huge_trace_steps) {
        if (!run_long_trace(app, scene, cam, rep)) return FrameReport{};
    } else {
        try {
            rep = render_frame(e.frame, e.world, scene, cam, e.frame_number);
        } catch (const Error& err) {
            return refuse_frame(app, err.what(), screenshot_mode);
        } catch (const std::bad_alloc&) {
            return refuse_frame(app, "out of memory tracing this frame: use a smaller view, area or fewer lights",
                                screenshot_mode);
        }
    }
    if (rep.retraced) renderer_upload_light(app.renderer, e.frame.traced, rep.dirty);  // only what changed
    renderer_upload_surface_ids(app.renderer, e.frame.surface_ids, e.frame.surface_ids_revision);
    CompositeOptions opts;
    opts.show_light = e.overlays.raw_light;
    const Overlays& ov = e.overlays;
    const bool want_truth = ov.truth_light || ov.truth_difference || (ov.split_view && ov.split_with_3d);
    const LightTexture* truth = want_truth ? update_truth(app, scene) : nullptr;
    // The renderer's second light texture: the 3D reference, or flat lighting.
    auto hold_truth = [&] {
        if (app.split_texture_holds != 2) renderer_upload_flat_light(app.renderer, *truth);
        app.split_texture_holds = 2;
    };
    if (truth && ov.truth_light) {
        hold_truth();
        opts.show_light = true;
        opts.split = 0;  // all of the view reads the second texture
    } else if (ov.split_view && truth && ov.split_with_3d) {
        hold_truth();
        opts.split = int(app.view.w * ov.split);
    } else if (ov.split_view) {
        Scene flat = scene;
        flat.params.mode = Mode::flat;
        app.flat_frame.options = e.frame.options;
        if (app.split_texture_holds != 1) app.flat_frame = FrameState{e.frame.options};  // retrace into it
        FrameReport fr;
        try {
            fr = render_frame(app.flat_frame, e.world, flat, cam, e.frame_number);
        } catch (const Error& err) {
            return refuse_frame(app, err.what(), screenshot_mode);
        }
        if (fr.retraced || app.split_texture_holds != 1) renderer_upload_flat_light(app.renderer, app.flat_frame.traced);
        app.split_texture_holds = 1;
        opts.split = int(app.view.w * ov.split);
    }
    // Overlays: rebuilt only when what they show changed.
    const Rect region = {app.view.x - 64, app.view.y - 64, app.view.w + 128, app.view.h + 128};
    const bool overlay_stale = !(app.overlay_key == e.overlays) || !(app.overlay_params == scene.params) ||
                               (ov.truth_difference && rep.retraced) ||
                               app.overlay_lights != scene.lights || rep.ran_stage(Stage::obstacle_map) ||
                               !(intersect(app.overlay_region, app.view) == app.view) || app.overlay_dirty;
    AccuracyPanel& acc = app.accuracy;
    const bool settings_changed = !(app.overlay_params == scene.params) || app.overlay_lights != scene.lights;
    if (acc.heatmap) {
        // The heat map replaces the other overlays while it is on; it is
        // recomputed (two CPU frames) only when the settings or view change.
        const bool wanted = acc.heatmap_stale || settings_changed || !(acc.heat.rect == app.view);
        // Made on the frame's thread: beyond the budget it is refused with its estimate.
        const double work = wanted ? reference_work(e.world, scene, app.view, acc.reference) +
                                         render_work(scene, app.view, 1)
                                   : 0;
        if (work > huge_trace_steps) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.2g", work);
            set_status(app.editor,
                       "the error heat map of this view would take about " + std::string(buf) +
                           " ray steps (minutes or more): use a smaller view, area or fewer lights",
                       true);
            acc.heatmap = false;
        } else if (wanted) {
            acc.heat = error_heatmap(e.world, scene, app.view, acc.reference, &acc.heat_metrics);
            acc.heatmap_stale = false;
            renderer_upload_overlay(app.renderer, acc.heat.image, acc.heat.rect);
        }
        app.overlay_params = scene.params;
        app.overlay_lights = scene.lights;
        app.overlay_dirty = true;  // rebuild the others when it is turned off
    } else if (overlay_stale) {
        OverlayImage o = build_overlays(e.world, e.frame, scene, e.overlays, region, truth);
        renderer_upload_overlay(app.renderer, o.image, o.rect);
        app.overlay_key = e.overlays;
        app.overlay_params = scene.params;
        app.overlay_lights = scene.lights;
        app.overlay_region = region;
        app.overlay_dirty = false;
    }
    renderer_draw(app.renderer, app.view, scene.params, opts);
    renderer_present(app.renderer, app.window_w, app.window_h, app.view_x, app.view_y, e.view.zoom, app.view);
    ++e.frame_number;
    return rep;
}

}  // namespace isolux::app
