// Accuracy against time: the metrics, the sweep and its CSV.
#include "isolux/accuracy.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <sstream>

#include "isolux/composite.hpp"
#include "isolux/error.hpp"
#include "isolux/truth.hpp"

namespace isolux {

namespace {

ErrorMetrics compare_raw(const std::uint8_t* a, const std::uint8_t* b, int w, int h, int channels, int lit_channels) {
    ErrorMetrics m;
    const std::size_t n = std::size_t(w) * h;
    if (n == 0) return m;
    std::size_t mismatch = 0, differing = 0;
    for (std::size_t i = 0; i < n; ++i) {
        bool lit_a = false, lit_b = false, diff = false;
        for (int k = 0; k < lit_channels; ++k) {
            lit_a = lit_a || a[i * channels + k] > 0;
            lit_b = lit_b || b[i * channels + k] > 0;
        }
        for (int k = 0; k < channels; ++k) diff = diff || a[i * channels + k] != b[i * channels + k];
        mismatch += lit_a != lit_b;
        differing += diff;
    }
    m.lit_mismatch = double(mismatch) / double(n);
    m.differing = double(differing) / double(n);
    // OpenImageIO for the error statistics (values normalised to [0, 1]).
    OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::UINT8);
    OIIO::ImageBuf A(spec, const_cast<std::uint8_t*>(a)), B(spec, const_cast<std::uint8_t*>(b));
    OIIO::ImageBufAlgo::CompareResults r = OIIO::ImageBufAlgo::compare(A, B, 1.0f, 1.0f);
    m.max_abs = int(std::lround(r.maxerror * 255.0));
    m.rmse = r.rms_error * 255.0;
    m.psnr = m.rmse > 0 ? 20.0 * std::log10(255.0 / m.rmse) : std::numeric_limits<double>::infinity();
    return m;
}

std::string params_key(const Params& p) {
    std::string k;
    for (const std::string& n : param_names()) k += get_param(p, n) + ";";
    return k;
}

std::string num(double v, int precision = 4) {
    if (std::isinf(v)) return "inf";
    std::ostringstream s;
    s.precision(precision);
    s << v;
    return s.str();
}

}  // namespace

ErrorMetrics compare_light(const LightTexture& test, const LightTexture& ref) {
    if (!(test.rect == ref.rect)) throw Error("compare_light: textures cover different rectangles");
    const LightTexture t = rgb_texture(test), r = rgb_texture(ref);  // either may be grey
    return compare_raw(t.texels.data(), r.texels.data(), test.rect.w, test.rect.h, 3, 3);
}

ErrorMetrics compare_images(const Image& test, const Image& ref) {
    if (test.width != ref.width || test.height != ref.height) throw Error("compare_images: sizes differ");
    return compare_raw(test.rgba.data(), ref.rgba.data(), test.width, test.height, 4, 3);
}

SweepAxis parse_sweep_axis(std::string_view text, const Params& base, std::string_view source) {
    const auto eq = text.find('=');
    if (eq == std::string_view::npos || eq == 0 || eq + 1 == text.size())
        throw Error(std::string(source) + " \"" + std::string(text) + "\": expected NAME=V1,V2,...");
    SweepAxis axis{std::string(text.substr(0, eq)), {}};
    const std::string_view rest = text.substr(eq + 1);
    for (std::size_t pos = 0;;) {
        const std::size_t end = rest.find(',', pos);
        axis.values.emplace_back(rest.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos));
        if (end == std::string_view::npos) break;
        pos = end + 1;
    }
    Params probe = base;
    for (const std::string& v : axis.values) set_param(probe, axis.name, v, source);
    return axis;
}

Params reference_params(Params p) {
    p.rays = Rays::every_pixel;
    p.ray_skip = 1;
    p.blur_radius = 0;
    p.trace_every = 1;
    return p;
}

std::vector<const SweepPoint*> pareto_front(const std::vector<SweepPoint>& points) {
    std::vector<const SweepPoint*> front;
    for (const SweepPoint& p : points)
        if (p.pareto) front.push_back(&p);
    std::stable_sort(front.begin(), front.end(), [](auto a, auto b) {
        if (a->reference != b->reference) return a->reference < b->reference;
        return a->lighting_ms < b->lighting_ms;
    });
    return front;
}

void mark_pareto(std::vector<SweepPoint>& points) {
    std::vector<std::size_t> order(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if (points[a].lighting_ms != points[b].lighting_ms) return points[a].lighting_ms < points[b].lighting_ms;
        return points[a].final.rmse < points[b].final.rmse;
    });
    // One front per reference: errors against different references do not compare.
    std::map<Reference, double> best;
    for (std::size_t i : order) {
        auto [it, fresh] = best.emplace(points[i].reference, std::numeric_limits<double>::infinity());
        points[i].pareto = points[i].final.rmse < it->second;
        it->second = std::min(it->second, points[i].final.rmse);
    }
}

void compare_in_areas(const LightTexture& model, const LightTexture& ref, const Surface& surface,
                      const std::vector<Rect>& areas, AreaErrors& floor, AreaErrors& sprite, AreaErrors& all) {
    const Rect r = surface.rect;
    double sq[3] = {0, 0, 0};
    long n[3] = {0, 0, 0}, mismatch[3] = {0, 0, 0};
    std::vector<char> inside(std::size_t(std::max(0, r.w)));
    for (int y = r.y; y < r.y + r.h; ++y) {
        std::fill(inside.begin(), inside.end(), 0);
        for (const Rect& a : areas) {
            if (y < a.y || y >= a.y + a.h) continue;
            const Rect row = intersect(a, Rect{r.x, y, r.w, 1});
            for (int x = row.x; x < row.x + row.w; ++x) inside[std::size_t(x - r.x)] = 1;
        }
        for (int x = r.x; x < r.x + r.w; ++x) {
            if (!inside[std::size_t(x - r.x)]) continue;
            const std::size_t i = std::size_t(y - r.y) * r.w + (x - r.x);
            const int kind = surface.instance[i] >= 0 ? 1 : 0;
            std::uint8_t a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
            for (int k = 0; k < 3; ++k) {
                if (model.rect.contains(x, y)) a[k] = model.value(x, y, k);
                if (ref.rect.contains(x, y)) b[k] = ref.value(x, y, k);
            }
            double e = 0;
            for (int k = 0; k < 3; ++k) e += double(a[k] - b[k]) * double(a[k] - b[k]);
            const bool lit_a = a[0] || a[1] || a[2], lit_b = b[0] || b[1] || b[2];
            for (int which : {kind, 2}) {
                sq[which] += e / 3;
                ++n[which];
                mismatch[which] += lit_a != lit_b;
            }
        }
    }
    AreaErrors* out[3] = {&floor, &sprite, &all};
    for (int k = 0; k < 3; ++k) {
        out[k]->pixels = n[k];
        out[k]->rmse = n[k] ? std::sqrt(sq[k] / double(n[k])) : 0;
        out[k]->lit_mismatch = n[k] ? double(mismatch[k]) / double(n[k]) : 0;
    }
}

namespace {

// Every combination of the axes' values, first axis slowest.
std::vector<std::vector<std::string>> combinations(const std::vector<SweepAxis>& axes) {
    std::vector<std::vector<std::string>> combos = {{}};
    for (const SweepAxis& a : axes) {
        if (a.values.empty()) throw Error("sweep axis " + a.name + ": no values");
        std::vector<std::vector<std::string>> next;
        for (const auto& c : combos)
            for (const std::string& v : a.values) {
                auto d = c;
                d.push_back(v);
                next.push_back(d);
            }
        combos = next;
    }
    return combos;
}

// One frame of the reference: its light texture over the view and its final image.
struct ReferenceFrame {
    LightTexture light;
    Image final;
    Surface surface;
    std::vector<Rect> areas;
};

std::size_t bytes_of(const ReferenceFrame& r) {
    return r.light.texels.size() + r.final.rgba.size() + r.surface.instance.size() * sizeof(std::int32_t) +
           r.surface.height.size() * sizeof(float);
}

// The sweep's reference frames by key, oldest dropped first beyond the budget
// (the newest always kept: a reference larger than the budget still serves
// the frame that asked for it).
class ReferenceCache {
public:
    const ReferenceFrame* find(const std::string& key) const {
        const auto it = frames_.find(key);
        return it == frames_.end() ? nullptr : &it->second;
    }
    const ReferenceFrame& add(const std::string& key, ReferenceFrame r) {
        bytes_ += bytes_of(r);
        order_.push_back(key);
        const ReferenceFrame& kept = frames_.emplace(key, std::move(r)).first->second;
        while (bytes_ > reference_cache_bytes && order_.size() > 1) {
            const auto old = frames_.find(order_.front());
            bytes_ -= bytes_of(old->second);
            frames_.erase(old);
            order_.pop_front();
        }
        return kept;
    }

private:
    std::map<std::string, ReferenceFrame> frames_;
    std::deque<std::string> order_;
    std::size_t bytes_ = 0;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    if (v.empty()) return 0;
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

void add_mean(AreaErrors& acc, const AreaErrors& m, int frames) {
    acc.lit_mismatch += m.lit_mismatch / frames;
    acc.rmse += m.rmse / frames;
    acc.pixels += m.pixels / frames;
}

}  // namespace

double sweep_work(const World& world, const Scene& scene, const std::vector<SweepAxis>& axes,
                  const SweepOptions& opt) {
    const Rect view = camera_view(scene.camera, world);
    Scene base = scene;
    if (opt.carry_light) {
        Light carried;
        carried.x = std::floor(view.x + view.w / 2.0) + 0.5;
        carried.y = std::floor(view.y + view.h / 2.0) + 0.5;
        base.lights.push_back(carried);
    }
    // Per frame of a combination: its rays and pixels on each run, and a
    // reference per reference (made again when the cache has dropped it);
    // the costliest value of each axis.
    const double pixels = double(view.w) * double(view.h) * view_pixel_steps;
    auto frame_work = [&](const Scene& s) {
        double reference = 0;
        for (Reference r : opt.references) reference += reference_work(world, s, view, r) + pixels;
        return (trace_work(s, view) + pixels) * std::max(1, opt.repeats) + reference;
    };
    double per_frame = frame_work(base);
    double combos = 1;
    for (const SweepAxis& ax : axes) {
        combos *= double(ax.values.size());
        for (const std::string& v : ax.values) {
            Scene probe = base;
            set_param(probe.params, ax.name, v, "sweep");
            per_frame = std::max(per_frame, frame_work(probe));
        }
    }
    return combos * std::max(1, opt.frames) * per_frame;
}

std::vector<SweepPoint> run_sweep(const World& world, const Scene& scene, const std::vector<SweepAxis>& axes,
                                  const SweepOptions& opt, const std::function<void(int, int)>& progress,
                                  const std::atomic<bool>* cancel) {
    const std::vector<std::vector<std::string>> combos = combinations(axes);
    std::vector<Params> params;
    for (const auto& c : combos) {
        Params p = scene.params;
        for (std::size_t i = 0; i < axes.size(); ++i) set_param(p, axes[i].name, c[i], "sweep axis");
        params.push_back(p);
    }
    const std::vector<Reference> references =
        opt.references.empty() ? std::vector<Reference>{Reference::every_pixel} : opt.references;

    const Rect start = camera_view(scene.camera, world);
    auto camera_at = [&](int f) {
        return Camera{start.x + opt.step_x * f, start.y + opt.step_y * f, start.w, start.h};
    };
    auto scene_at = [&](const Params& p, int f) {
        Scene s = scene;
        s.params = p;
        if (opt.carry_light) {
            const Camera c = camera_at(f);
            Light carried;
            carried.x = std::floor(c.x + c.width / 2.0) + 0.5;
            carried.y = std::floor(c.y + c.height / 2.0) + 0.5;
            s.lights.push_back(carried);
        }
        return s;
    };
    // A combination tracing the manifest's shapes, where a sprite its frames
    // need has none, is refused before the first combination runs, not after
    // the ones before it (require_shapes names the sprite): the first frame's
    // whole region, then what each later frame needs (a later frame builds
    // the room around it only if the camera left the region before).
    for (const Params& p : params)
        if (p.occluders == Occluders::shapes && p.mode != Mode::flat)
            for (int f = 0; f < std::max(1, opt.frames); ++f) {
                const Rect needed = frame_region_needed(world, scene_at(p, f), camera_at(f), FrameOptions{}.margin);
                require_shapes(world, f > 0 ? needed : obstacle_region_around(needed, world));
            }

    // References, one per frame, shared by the combinations whose parameters
    // the reference does not read (ray skip, rays, blur and l), in a cache of
    // at most reference_cache_bytes: beyond it the oldest are dropped and made
    // again when asked for (sweep_work counts a reference per combination, so
    // the estimate holds either way), and memory stays bounded whatever the
    // axes' lengths.
    ReferenceCache refs;
    auto reference = [&](const Params& p, Reference which, int f) -> const ReferenceFrame& {
        const Params rp = reference_params(p);
        const std::string key = std::string(to_string(which)) + (opt.opacity_correction ? ":" : ":raw:") +
                                params_key(rp) + "@" + std::to_string(f);
        if (const ReferenceFrame* hit = refs.find(key)) return *hit;
        const Scene s = scene_at(rp, f);
        const Rect view = camera_view(camera_at(f), world);
        ReferenceFrame r;
        r.light = reference_texture(world, s, view, which, opt.opacity_correction);
        r.final = composite(render_sprites(world.tileset, world.placed, view), view, r.light, rp);
        r.surface = build_surface(world, view, rp.opacity_threshold);
        for (const Light& l : s.lights) r.areas.push_back(light_area(l, rp));
        return refs.add(key, std::move(r));
    };

    std::vector<SweepPoint> out;
    const int total = int(params.size() * references.size());
    for (std::size_t c = 0; c < params.size(); ++c) {
        if (cancel && cancel->load()) break;
        // One point per reference; the first repeat's frames are compared as
        // they are made (never all kept: a long --frames stays in one frame's memory).
        std::vector<SweepPoint> points(references.size());
        auto compare_frame = [&](const FrameState& st, int f) {
            for (std::size_t k = 0; k < references.size(); ++k) {
                SweepPoint& pt = points[k];
                const ReferenceFrame& ref = reference(params[c], references[k], f);
                const ErrorMetrics l = compare_light(st.light, ref.light);
                const ErrorMetrics fi = compare_images(st.final, ref.final);
                for (auto [acc, m] : {std::pair{&pt.light, &l}, std::pair{&pt.final, &fi}}) {
                    acc->lit_mismatch += m->lit_mismatch / opt.frames;
                    acc->differing += m->differing / opt.frames;
                    acc->rmse += m->rmse / opt.frames;
                    acc->max_abs = std::max(acc->max_abs, m->max_abs);
                }
                AreaErrors fl, sp, all;
                compare_in_areas(st.light, ref.light, ref.surface, ref.areas, fl, sp, all);
                add_mean(pt.floor, fl, opt.frames);
                add_mean(pt.sprite, sp, opt.frames);
                add_mean(pt.area, all, opt.frames);
            }
        };
        // Times: each repeat's mean per frame; the median over repeats, and the spread.
        std::array<std::vector<double>, stage_count> runs;
        for (int rep = 0; rep < std::max(1, opt.repeats); ++rep) {
            FrameState st;
            st.options.opacity_correction = opt.opacity_correction;
            st.options.control.cancel = cancel;  // a long frame stops mid-trace too
            std::array<double, stage_count> sum{};
            for (int f = 0; f < opt.frames; ++f) {
                FrameReport r;
                try {
                    r = render_frame(st, world, scene_at(params[c], f), camera_at(f), f);
                    if (rep == 0) compare_frame(st, f);
                } catch (const Cancelled&) {
                    return out;  // the combinations done so far
                }
                for (int k = 0; k < stage_count; ++k) sum[k] += r.ms[k];
            }
            for (int k = 0; k < stage_count; ++k) runs[k].push_back(sum[k] / opt.frames);
        }
        SweepPoint timed;
        timed.params = params[c];
        timed.values = combos[c];
        std::vector<double> lighting_runs(runs[0].size(), 0);
        for (int k = 0; k < stage_count; ++k) {
            timed.ms[k] = median(runs[k]);
            timed.total_ms += timed.ms[k];
            const Stage st = Stage(k);
            if (st != Stage::sprites && st != Stage::composite) {
                timed.lighting_ms += timed.ms[k];
                for (std::size_t r = 0; r < runs[k].size(); ++r) lighting_runs[r] += runs[k][r];
            }
            if (st == Stage::obstacle_map || st == Stage::trace || st == Stage::opacity_correction)
                timed.app_cpu_ms += timed.ms[k];
            if (st == Stage::blur || st == Stage::shift || st == Stage::composite) timed.cpu_only_ms += timed.ms[k];
        }
        timed.lighting_min_ms = *std::min_element(lighting_runs.begin(), lighting_runs.end());
        timed.lighting_max_ms = *std::max_element(lighting_runs.begin(), lighting_runs.end());

        for (std::size_t k = 0; k < references.size(); ++k) {
            SweepPoint pt = timed;
            pt.reference = references[k];
            pt.light = points[k].light;
            pt.final = points[k].final;
            pt.floor = points[k].floor;
            pt.sprite = points[k].sprite;
            pt.area = points[k].area;
            for (ErrorMetrics* m : {&pt.light, &pt.final})
                m->psnr = m->rmse > 0 ? 20.0 * std::log10(255.0 / m->rmse) : std::numeric_limits<double>::infinity();
            out.push_back(pt);
            if (opt.rows_so_far) opt.rows_so_far(out);
            if (progress) progress(int(out.size()), total);
        }
    }
    mark_pareto(out);
    return out;
}

std::string sweep_csv(const std::vector<SweepAxis>& axes, const std::vector<SweepPoint>& points, bool pareto_known) {
    std::ostringstream s;
    for (const SweepAxis& a : axes) s << a.name << ",";
    for (int k = 0; k < stage_count; ++k) s << "ms_" << to_string(Stage(k)) << ",";
    s << "ms_total,ms_lighting";
    for (const char* which : {"light", "final"})
        for (const char* m : {"lit_mismatch", "differing", "max_abs", "rmse", "psnr"}) s << "," << which << "_" << m;
    s << ",pareto,reference,ms_lighting_min,ms_lighting_max,ms_app_cpu,ms_cpu_only";
    for (const char* which : {"floor", "sprite", "area"})
        for (const char* m : {"lit_mismatch", "rmse", "pixels"}) s << "," << which << "_" << m;
    s << "\n";
    for (const SweepPoint& p : points) {
        for (const std::string& v : p.values) s << v << ",";
        for (int k = 0; k < stage_count; ++k) s << num(p.ms[k], 5) << ",";
        s << num(p.total_ms, 5) << "," << num(p.lighting_ms, 5);
        for (const ErrorMetrics* m : {&p.light, &p.final})
            s << "," << num(m->lit_mismatch, 6) << "," << num(m->differing, 6) << "," << m->max_abs << ","
              << num(m->rmse, 5) << "," << num(m->psnr, 5);
        s << "," << (pareto_known ? (p.pareto ? "1" : "0") : "") << "," << to_string(p.reference) << "," << num(p.lighting_min_ms, 5) << ","
          << num(p.lighting_max_ms, 5) << "," << num(p.app_cpu_ms, 5) << "," << num(p.cpu_only_ms, 5);
        for (const AreaErrors* m : {&p.floor, &p.sprite, &p.area})
            s << "," << num(m->lit_mismatch, 6) << "," << num(m->rmse, 5) << "," << m->pixels;
        s << "\n";
    }
    return s.str();
}

}  // namespace isolux
