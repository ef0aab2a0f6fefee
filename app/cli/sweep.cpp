#include "cli/sweep.hpp"
#include "cli/sweep_chart.hpp"

#include <filesystem>
#include <iostream>

#include "cli/args.hpp"
#include "common/world.hpp"
#include "isolux/accuracy.hpp"
#include "isolux/error.hpp"
#include "isolux/file_io.hpp"
#include "isolux/isolux.hpp"
#include "isolux/frame.hpp"
#include "isolux/scene_file.hpp"
#include "isolux/truth.hpp"

namespace isolux::cli {

using namespace isolux::app;

int run_sweep_command(const SweepArgs& a) {
    // Outputs checked before the work, not after it.
    check_output_file(a.out);
    if (!a.chart.empty()) check_output_file(a.chart);
    std::vector<std::string> warnings;
    Scene s = load_scene(a.scene, &warnings);
    for (const auto& w : warnings) std::cerr << "isolux-cli: warning: " << printable(w) << "\n";
    std::vector<SweepAxis> axes;
    for (const std::string& text : a.params) axes.push_back(parse_sweep_axis(text, s.params, "--param"));
    for (const SweepAxis& ax : axes) {
        const std::string note = overridden_by_lights(ax.name, "--param " + ax.name, s.lights);
        if (!note.empty()) std::cerr << "isolux-cli: note: " << note << "\n";
    }
    std::vector<double> step;
    if (!parse_reals(a.step, step) || step.size() != 2) throw Error("--step \"" + a.step + "\": expected DX,DY");
    SweepOptions opt;
    opt.frames = a.frames;
    opt.repeats = a.repeats;
    opt.step_x = step[0];
    opt.step_y = step[1];
    opt.carry_light = !a.no_carry;
    opt.opacity_correction = !a.no_opacity_correction;
    opt.references.clear();
    for (std::size_t pos = 0;;) {
        const std::size_t end = a.references.find(',', pos);
        opt.references.push_back(parse_reference(a.references.substr(pos, end == std::string::npos ? end : end - pos),
                                                 "--reference"));
        if (end == std::string::npos) break;
        pos = end + 1;
    }
    World w = build_world(s, a.scene);
    check_work(sweep_work(w, s, axes, opt), a.allow_huge, "this sweep");  // before any of it starts
    long combos = 1;
    for (const SweepAxis& ax : axes) combos *= long(ax.values.size());
    std::cerr << "isolux-cli: sweeping " << combos << " combinations x " << opt.repeats << " runs x " << opt.frames
              << " frames, against " << a.references << "\n";
    // Each row written as it is measured (the pareto column empty until the
    // end), so a sweep stopped midway keeps what it measured.
    opt.rows_so_far = [&](const std::vector<SweepPoint>& so_far) { write_file_atomic(a.out, sweep_csv(axes, so_far, false)); };
    auto points = run_sweep(w, s, axes, opt, [&](int done, int total) {
        std::cerr << "\r  [" << done << "/" << total << "] " << int(100.0 * done / total) << "%" << std::flush;
    });
    std::cerr << "\n";
    write_file_atomic(a.out, sweep_csv(axes, points));
    std::cout << "wrote " << a.out << "\n";
    if (!a.chart.empty()) {
        const Rect start = camera_view(s.camera, w);
        const std::string what = std::filesystem::path(a.scene).filename().string() + " (seed \"" + s.seed + "\"), " +
                                 std::to_string(opt.frames) + " frames from view " + std::to_string(start.x) + "," +
                                 std::to_string(start.y) + " " + std::to_string(start.w) + "x" + std::to_string(start.h) +
                                 " moving " + a.step + " px a frame, against " + a.references;
        write_file_atomic(a.chart, sweep_svg(axes, points, "Error against time\n" + what));
        std::cout << "wrote " << a.chart << "\n";
    }
    std::cout << "Pareto front (least final-frame RMSE for the time), per reference:\n";
    for (const SweepPoint* p : pareto_front(points)) {
        std::cout << "  [" << to_string(p->reference) << "] ";
        for (std::size_t i = 0; i < axes.size(); ++i) std::cout << axes[i].name << "=" << p->values[i] << " ";
        std::cout << " " << p->lighting_ms << " ms/frame lighting (" << p->total_ms << " in all), final RMSE " << p->final.rmse << ", lit mismatch "
                  << p->light.lit_mismatch * 100 << "%\n";
    }
    return 0;
}

}  // namespace isolux::cli
