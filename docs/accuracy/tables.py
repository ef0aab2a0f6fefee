#!/usr/bin/env python3
"""Prints the Markdown tables of docs/accuracy.md from the sweeps' CSVs:
python3 docs/accuracy/tables.py (after running the sweeps the doc names)."""
import csv, os

HERE = os.path.dirname(os.path.abspath(__file__))


def rows(name):
    return list(csv.DictReader(open(os.path.join(HERE, name + ".csv"))))


def fmt(v, n=3):
    f = float(v)
    return "inf" if f == float("inf") else f"{f:.{n}g}"


def pct(v):
    return f"{float(v) * 100:.2f}%"


def pareto(name):
    out = ["| k | blur | l | lighting ms | trace ms | lit mismatch | light max | final RMSE | final PSNR |",
           "|---|---|---|---|---|---|---|---|---|"]
    for r in sorted((r for r in rows(name) if r["pareto"] == "1"), key=lambda r: float(r["ms_lighting"])):
        out.append("| " + " | ".join([r["ray_skip"], r["blur_radius"], r["trace_every"], fmt(r["ms_lighting"]),
                                      fmt(r["ms_trace"]), pct(r["light_lit_mismatch"]), r["light_max_abs"],
                                      fmt(r["final_rmse"]), fmt(r["final_psnr"]) + " dB"]) + " |")
    return "\n".join(out)


def every_frame(name):
    out = ["| k | blur | lighting ms | trace ms | blur ms | lit mismatch | final RMSE | final PSNR |",
           "|---|---|---|---|---|---|---|---|"]
    for r in rows(name):
        if r["trace_every"] == "1":
            out.append("| " + " | ".join([r["ray_skip"], r["blur_radius"], fmt(r["ms_lighting"]), fmt(r["ms_trace"]),
                                          fmt(r["ms_blur"]), pct(r["light_lit_mismatch"]), fmt(r["final_rmse"]),
                                          fmt(r["final_psnr"]) + " dB"]) + " |")
    return "\n".join(out)


def areas(name):
    out = ["| a | k | rays | lighting ms | trace ms | lit mismatch | final RMSE |", "|---|---|---|---|---|---|---|"]
    for r in rows(name):
        out.append("| " + " | ".join([r["area_a"], r["ray_skip"], r["rays"], fmt(r["ms_lighting"]), fmt(r["ms_trace"]),
                                      pct(r["light_lit_mismatch"]), fmt(r["final_rmse"])]) + " |")
    return "\n".join(out)


if __name__ == "__main__":
    for n in ("default", "forest"):
        print(f"## {n}: Pareto front\n\n{pareto(n)}\n\n## {n}: l = 1\n\n{every_frame(n)}\n")
    print(f"## forest_area\n\n{areas('forest_area')}")
