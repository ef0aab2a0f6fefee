"""Helpers of scripts/app_profile.sh: the scene it runs, and the comparison
of perf's samples with the app's frame report."""
import json
import re
import sys

# Which stage each sampled function works for (a substring of its symbol).
# The frame report counts adding lights into the texture in `trace`.
STAGE_OF = [
    ("walk_tree", "trace"),
    ("trace_light_into", "trace"),
    ("trace_fast", "trace"),
    ("prune_tree", "trace"),
    ("obstacle_pixels", "trace"),
    ("copy_area_rows", "trace"),
    ("tree_values", "trace"),
    ("area_is_clear", "trace"),
    ("accumulate_light", "trace"),
    ("add_white_row", "trace"),
    ("add_grey_row", "trace"),
    ("add_row", "trace"),
    ("trace_and_accumulate", "trace"),
    ("correct_lines", "opacity_correction"),
    ("correct_with", "opacity_correction"),
    ("count_instances_in", "opacity_correction"),
    ("build_obstacle_map", "obstacle_map"),
    ("noise_filter", "obstacle_map"),
    ("ground_lines", "obstacle_map"),
    ("render_sprites", "sprites"),
    ("box_blur", "blur"),
    ("blur_small", "blur"),
    ("shade_row", "composite"),
]


def scene(path):
    # Pcg-free and fixed: a 12x12 default map (world about 1540 x 900), 32
    # lights on a grid with a stagger, so that they cover the view.
    lights = []
    for i in range(32):
        x = 130 + (i % 8) * 175 + (i // 8) * 40
        y = 120 + (i // 8) * 190 + (i % 3) * 20
        lights.append({"x": x + 0.5, "y": y + 0.5, "color": "ffffff", "intensity": 1.0})
    doc = {"schema_version": 1, "seed": "isolux", "width": 12, "height": 12, "layout": "diamond", "tileset": "",
           "preset": {"ambient_clarity": 0.3, "falloff_scale": 8, "area_a": 128, "area_b": 128, "blur_radius": 2},
           "lights": lights, "camera": {"x": 0, "y": 0, "width": 0, "height": 0}}
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)


def compare(stats_path, perf_path):
    stats = json.load(open(stats_path))
    samples = {}
    other = 0.0
    others = []
    for line in open(perf_path):
        m = re.match(r"\s*([0-9.]+)%\s+\[\.\]\s+(.*)$", line)
        if not m:
            continue
        share, sym = float(m.group(1)), m.group(2).strip()
        stage = next((st for key, st in STAGE_OF if key in sym), None)
        if stage:
            samples[stage] = samples.get(stage, 0.0) + share
        else:
            other += share
            others.append((share, sym))
    cpu = stats["cpu_ms"]
    stages = [s for s in cpu if cpu[s] > 0 or samples.get(s, 0) > 0]
    report_total = sum(cpu[s] for s in stages)
    perf_total = sum(samples.get(s, 0) for s in stages)
    print(f"app frame: {stats['frames']} frames, {stats['lights_traced']} lights traced in the last, "
          f"tracer {stats['tracer']}, frame {stats['frame_ms']:.2f} ms")
    print(f"{'stage':<20} {'report ms':>10} {'report %':>9} {'perf %':>8}")
    for s in stages:
        r = 100 * cpu[s] / report_total if report_total else 0
        p = 100 * samples.get(s, 0) / perf_total if perf_total else 0
        print(f"{s:<20} {cpu[s]:>10.3f} {r:>8.1f}% {p:>7.1f}%")
    gpu = stats["gpu_ms"]
    print("GPU stages, by GL timer queries (on Mesa's llvmpipe, the CPU's llvmpipe threads): " +
          ", ".join(f"{k} {v:.2f} ms" for k, v in gpu.items() if v > 0))
    print(f"samples of the app's threads in no stage's functions: {other:.1f}% "
          f"(the largest: {', '.join(f'{sym} {sh:.1f}%' for sh, sym in sorted(others, reverse=True)[:5])})")


if __name__ == "__main__":
    if sys.argv[1] == "scene":
        scene(sys.argv[2])
    else:
        compare(sys.argv[2], sys.argv[3])
