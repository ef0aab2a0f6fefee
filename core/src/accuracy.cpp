// Accuracy against time: the metrics, the sweep, its CSV and chart.
#include "isolux/accuracy.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "isolux/error.hpp"

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
    return compare_raw(test.rgb.data(), ref.rgb.data(), test.rect.w, test.rect.h, 3, 3);
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
    std::stable_sort(front.begin(), front.end(), [](auto a, auto b) { return a->lighting_ms < b->lighting_ms; });
    return front;
}

void mark_pareto(std::vector<SweepPoint>& points) {
    std::vector<std::size_t> order(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if (points[a].lighting_ms != points[b].lighting_ms) return points[a].lighting_ms < points[b].lighting_ms;
        return points[a].final.rmse < points[b].final.rmse;
    });
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i : order) {
        points[i].pareto = points[i].final.rmse < best;
        best = std::min(best, points[i].final.rmse);
    }
}

std::vector<SweepPoint> run_sweep(const World& world, const Scene& scene, const std::vector<SweepAxis>& axes,
                                  const SweepOptions& opt, const std::function<void(int, int)>& progress,
                                  const std::atomic<bool>* cancel) {
    // Every combination, first axis slowest.
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
    std::vector<Params> params;
    for (const auto& c : combos) {
        Params p = scene.params;
        for (std::size_t i = 0; i < axes.size(); ++i) set_param(p, axes[i].name, c[i], "sweep axis");
        params.push_back(p);
    }

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

    // References: a fresh every-pixel trace per frame, shared by the
    // combinations that differ only in ray skip, rays, blur and l.
    struct Ref {
        std::vector<LightTexture> light;
        std::vector<Image> final;
    };
    std::map<std::string, Ref> refs;
    auto reference = [&](const Params& p) -> const Ref& {
        const Params rp = reference_params(p);
        const std::string key = params_key(rp);
        auto it = refs.find(key);
        if (it != refs.end()) return it->second;
        Ref r;
        for (int f = 0; f < opt.frames; ++f) {
            FrameState st;
            render_frame(st, world, scene_at(rp, f), camera_at(f), 0);
            r.light.push_back(st.light);
            r.final.push_back(st.final);
        }
        return refs.emplace(key, std::move(r)).first->second;
    };

    std::vector<SweepPoint> out;
    for (std::size_t c = 0; c < params.size(); ++c) {
        if (cancel && cancel->load()) break;
        SweepPoint pt;
        pt.params = params[c];
        pt.values = combos[c];
        const Ref& ref = reference(pt.params);
        std::array<std::vector<double>, stage_count> runs;
        for (int rep = 0; rep < std::max(1, opt.repeats); ++rep) {
            FrameState st;
            std::array<double, stage_count> sum{};
            for (int f = 0; f < opt.frames; ++f) {
                FrameReport r = render_frame(st, world, scene_at(pt.params, f), camera_at(f), f);
                for (int k = 0; k < stage_count; ++k) sum[k] += r.ms[k];
                if (rep == 0) {
                    const ErrorMetrics l = compare_light(st.light, ref.light[f]);
                    const ErrorMetrics fi = compare_images(st.final, ref.final[f]);
                    for (auto [acc, m] : {std::pair{&pt.light, &l}, std::pair{&pt.final, &fi}}) {
                        acc->lit_mismatch += m->lit_mismatch / opt.frames;
                        acc->differing += m->differing / opt.frames;
                        acc->rmse += m->rmse / opt.frames;
                        acc->max_abs = std::max(acc->max_abs, m->max_abs);
                    }
                }
            }
            for (int k = 0; k < stage_count; ++k) runs[k].push_back(sum[k] / opt.frames);
        }
        for (ErrorMetrics* m : {&pt.light, &pt.final})
            m->psnr = m->rmse > 0 ? 20.0 * std::log10(255.0 / m->rmse) : std::numeric_limits<double>::infinity();
        for (int k = 0; k < stage_count; ++k) {
            std::vector<double>& v = runs[k];
            std::sort(v.begin(), v.end());
            pt.ms[k] = v[v.size() / 2];
            pt.total_ms += pt.ms[k];
            if (k != int(Stage::sprites) && k != int(Stage::composite)) pt.lighting_ms += pt.ms[k];
        }
        out.push_back(pt);
        if (progress) progress(int(c + 1), int(params.size()));
    }
    mark_pareto(out);
    return out;
}

std::string sweep_csv(const std::vector<SweepAxis>& axes, const std::vector<SweepPoint>& points) {
    std::ostringstream s;
    for (const SweepAxis& a : axes) s << a.name << ",";
    for (int k = 0; k < stage_count; ++k) s << "ms_" << to_string(Stage(k)) << ",";
    s << "ms_total,ms_lighting";
    for (const char* which : {"light", "final"})
        for (const char* m : {"lit_mismatch", "differing", "max_abs", "rmse", "psnr"}) s << "," << which << "_" << m;
    s << ",pareto\n";
    for (const SweepPoint& p : points) {
        for (const std::string& v : p.values) s << v << ",";
        for (int k = 0; k < stage_count; ++k) s << num(p.ms[k], 5) << ",";
        s << num(p.total_ms, 5) << "," << num(p.lighting_ms, 5);
        for (const ErrorMetrics* m : {&p.light, &p.final})
            s << "," << num(m->lit_mismatch, 6) << "," << num(m->differing, 6) << "," << m->max_abs << ","
              << num(m->rmse, 5) << "," << num(m->psnr, 5);
        s << "," << (p.pareto ? 1 : 0) << "\n";
    }
    return s.str();
}

std::string sweep_svg(const std::vector<SweepAxis>& axes, const std::vector<SweepPoint>& points,
                      const std::string& title) {
    const double W = 760, H = 460, L = 70, R = 20, T = 40, B = 60;
    double tmin = 1e300, tmax = 0, emax = 0;
    for (const SweepPoint& p : points) {
        tmin = std::min(tmin, p.lighting_ms);
        tmax = std::max(tmax, p.lighting_ms);
        emax = std::max(emax, p.final.rmse);
    }
    if (points.empty()) tmin = 0, tmax = 1;
    const bool log_x = tmin > 0 && tmax / tmin > 8;
    auto fx = [&](double t) {
        double u = log_x ? (std::log(t) - std::log(tmin)) / std::max(1e-12, std::log(tmax) - std::log(tmin))
                         : (t - 0) / std::max(1e-12, tmax);
        return L + u * (W - L - R);
    };
    emax = emax > 0 ? emax * 1.1 : 1;
    auto fy = [&](double e) { return H - B - e / emax * (H - T - B); };
    std::ostringstream s;
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << W / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << title << "</text>\n"
      << "<line x1=\"" << L << "\" y1=\"" << H - B << "\" x2=\"" << W - R << "\" y2=\"" << H - B << "\" stroke=\"black\"/>\n"
      << "<line x1=\"" << L << "\" y1=\"" << T << "\" x2=\"" << L << "\" y2=\"" << H - B << "\" stroke=\"black\"/>\n";
    for (int i = 0; i <= 4; ++i) {
        const double t = log_x ? tmin * std::pow(tmax / tmin, i / 4.0) : tmax * i / 4.0;
        const double e = emax * i / 4.0;
        s << "<text x=\"" << fx(t) << "\" y=\"" << H - B + 16 << "\" text-anchor=\"middle\">" << num(t, 3) << "</text>\n"
          << "<text x=\"" << L - 6 << "\" y=\"" << fy(e) + 4 << "\" text-anchor=\"end\">" << num(e, 3) << "</text>\n";
    }
    s << "<text x=\"" << (L + W - R) / 2 << "\" y=\"" << H - 18 << "\" text-anchor=\"middle\">lighting time per frame (median), ms"
      << (log_x ? " (log scale)" : "") << "</text>\n"
      << "<text transform=\"translate(16," << (T + H - B) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">final frame RMSE vs reference (0-255)</text>\n";
    const std::vector<const SweepPoint*> front = pareto_front(points);
    if (front.size() > 1) {
        s << "<polyline fill=\"none\" stroke=\"#e07020\" stroke-width=\"1.5\" points=\"";
        for (const SweepPoint* p : front) s << fx(p->lighting_ms) << "," << fy(p->final.rmse) << " ";
        s << "\"/>\n";
    }
    for (const SweepPoint& p : points) {
        std::string label;
        for (std::size_t i = 0; i < axes.size(); ++i) label += (i ? " " : "") + axes[i].name + "=" + p.values[i];
        s << "<g><title>" << label << ": " << num(p.lighting_ms, 4) << " ms, RMSE " << num(p.final.rmse, 4)
          << "</title><circle cx=\"" << fx(p.lighting_ms) << "\" cy=\"" << fy(p.final.rmse) << "\" r=\""
          << (p.pareto ? 5 : 3.5) << "\" fill=\"" << (p.pareto ? "#e07020" : "#4070c0") << "\"/></g>\n";
        if (p.pareto)
            s << "<text x=\"" << fx(p.lighting_ms) + 7 << "\" y=\"" << fy(p.final.rmse) - 6 << "\" font-size=\"10\">" << label
              << "</text>\n";
    }
    s << "<text x=\"" << W - R << "\" y=\"" << T << "\" text-anchor=\"end\" fill=\"#e07020\">orange: Pareto front (least error for the time)</text>\n";
    s << "</svg>\n";
    return s.str();
}

}  // namespace isolux
