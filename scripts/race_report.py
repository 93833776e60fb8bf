#!/usr/bin/env python3
"""Joins the two sides of scripts/race-cell-fracture.sh into one Google-Benchmark-shaped JSON
file (bench_race_cell_fracture.json), so tests/bench/write_benchmarks_md.py makes it a section
of docs/BENCHMARKS.md like any benchmark binary's.

Rows, per piece count N: `Blender_CellFracture/pieces:N` (time = the operator) and
`Fissure_BodyPrepared/pieces:N/tets:T` (time = simulation + closed meshes, BM_Race's median),
each with its pieces, closed pieces, volume error and whole-process seconds; the Fissure row
also carries `speedup` = Blender's operator time / Fissure's time, `process_speedup` the same
for whole processes. Then this run's bench_machine rows, to compare runs on other machines.
Usage: race_report.py FISSURE_JSON BLENDER_JSONL PROCESS_JSONL MACHINE_JSON OUT_JSON
"""
import json
import sys


def medians(benchmarks):
    rows = [b for b in benchmarks if b.get("aggregate_name", "median") == "median"]
    return rows or [b for b in benchmarks if "aggregate_name" not in b]


def ms(b):
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
    return b["real_time"] * scale


def machine_rows(machine):
    """bench_machine's median rows, named `machine: …`, for a race's table."""
    rows = []
    for b in medians(machine["benchmarks"]):
        row = {k: v for k, v in b.items() if k in ("real_time", "time_unit", "GB_per_s", "working_set_MB", "GFLOPs")}
        row["name"] = "machine: " + b.get("run_name", b["name"])
        rows.append(row)
    return rows


def main():
    fissure_json, blender_jsonl, process_jsonl, machine_json, out = sys.argv[1:6]
    fissure = json.load(open(fissure_json))
    blender = {d["seeds"]: d for d in map(json.loads, open(blender_jsonl))}
    process = {d["pieces"]: d for d in map(json.loads, open(process_jsonl))}
    rows = []
    for b in medians(fissure["benchmarks"]):
        name = b.get("run_name", b["name"])
        pieces = int(name.split("pieces:")[1].split("/")[0])
        cf = blender.get(pieces)
        cf_ms = cf["seconds"] * 1e3 if cf else None
        if cf:
            rows.append({"name": f"Blender_CellFracture/pieces:{pieces}", "real_time": cf_ms, "time_unit": "ms",
                         "pieces": cf["pieces"], "closed": cf["closed"], "closed_as_made": cf["closed_as_made"],
                         "volume_err": cf["volume_err"], "process_s": cf["process_s"]})
        p = process.get(pieces, {})
        row = {"name": f"Fissure_BodyPrepared/pieces:{pieces}/tets:{int(b['tets'])}", "real_time": ms(b),
               "time_unit": "ms", "pieces": b["pieces"], "closed": b["closed"], "volume_err": b["volume_err"],
               "fissure_threads": b["fissure_threads"], "cracks": b["cracks"],
               "simulation_ms": b["simulation_ms"], "meshing_ms": b["meshing_ms"]}
        if p:
            row["process_s"] = p["process_s"]
            row["process_pieces"] = p["meshes"]
        if cf_ms:
            row["speedup"] = cf_ms / ms(b)
            if p:
                row["process_speedup"] = cf["process_s"] / p["process_s"]
        rows.append(row)
    rows += machine_rows(json.load(open(machine_json)))
    with open(out, "w") as f:
        json.dump({"context": fissure.get("context", {}), "benchmarks": rows}, f, indent=1)


if __name__ == "__main__":
    main()
