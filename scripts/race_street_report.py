#!/usr/bin/env python3
"""Joins the sides of scripts/race-street-cell-fracture.sh into one Google-Benchmark-shaped JSON
file (bench_race_street_cell_fracture.json), so tests/bench/write_benchmarks_md.py makes it a
section of docs/BENCHMARKS.md like any benchmark binary's.

Rows (medians over the repetitions):
  `Fissure_Street/cache:C` (C = cold, warm): time = the whole process, start to exit; `bodies`,
      `pieces` (fragments written), `closed` (closed in Blender after Merge Vertices); `bodies_s`:
      the bodies' seconds summed over both threads, with the shares of meshing, preparation,
      simulation and fragments in it; `speedup`: Blender's process time / Fissure's.
  `Blender_CellFracture_Street`: time = the whole process (import, one Cell Fracture call over
      every body, GLB export); `fracture_s` the operator alone, `import_s`, `export_s`; `pieces`,
      `closed` after Merge by Distance, `closed_as_made`, `volume_err` against the bodies' volumes.
Then this run's bench_machine rows, to compare runs on other machines.
Usage: race_street_report.py FISSURE_JSONL FISSURE_CHECK_JSON BLENDER_JSONL MACHINE_JSON OUT_JSON
"""
import json
import statistics
import sys

from race_report import machine_rows

STAGES = ("meshing", "preparation", "simulation", "fragments")


def median_of(rows, key):
    return statistics.median(r[key] for r in rows)


def fissure_row(runs, check, blender_process_s):
    report = runs[0]["report"]
    fractured = [b for b in report["bodies"] if b["status"] == "fractured"]
    stage_s = {s: statistics.median(sum(b["seconds"][s] for b in r["report"]["bodies"] if b["status"] == "fractured")
                                    for r in runs) for s in STAGES}
    bodies_s = sum(stage_s.values())
    process_s = median_of(runs, "process_s")
    row = {"name": f"Fissure_Street/cache:{runs[0]['cache']}", "real_time": process_s * 1e3, "time_unit": "ms",
           "bodies": len(fractured), "pieces": sum(b["fragments"] for b in fractured),
           "per_body_s": process_s / len(fractured), "bodies_s": bodies_s, "closed": check["closed"]}
    for s in STAGES:
        row[s] = stage_s[s] / bodies_s
    row["speedup"] = blender_process_s / process_s
    return row


def main():
    fissure_jsonl, check_json, blender_jsonl, machine_json, out = sys.argv[1:6]
    runs = [json.loads(line) for line in open(fissure_jsonl)]
    check = json.load(open(check_json))
    blender = [json.loads(line) for line in open(blender_jsonl)]
    blender_process_s = median_of(blender, "process_s")
    rows = [fissure_row([r for r in runs if r["cache"] == c], check, blender_process_s) for c in ("cold", "warm")]
    last = blender[-1]
    rows.append({"name": "Blender_CellFracture_Street", "real_time": blender_process_s * 1e3, "time_unit": "ms",
                 "bodies": last["bodies"], "pieces": last["pieces"], "closed": last["closed"],
                 "closed_as_made": last["closed_as_made"], "volume_err": last["volume_err"],
                 "per_body_s": blender_process_s / last["bodies"],
                 "fracture_s": median_of(blender, "seconds"), "import_s": median_of(blender, "import_s"),
                 "export_s": median_of(blender, "export_s")})
    machine = json.load(open(machine_json))
    rows += machine_rows(machine)
    with open(out, "w") as f:
        json.dump({"context": machine.get("context", {}), "benchmarks": rows}, f, indent=1)


if __name__ == "__main__":
    main()
