#!/usr/bin/env python3
"""Writes docs/BENCHMARKS.md from Google Benchmark JSON files.

Every benchmark binary writes <name>.json; this script turns the median aggregates into one
table per binary, keeps the counters (tet counts, errors, memory) as columns, and stamps the
machine, the commit and the command. Sections named in SECTION_NOTES get a short explanation.
Usage: write_benchmarks_md.py RESULTS_DIR OUTPUT_MD COMMAND
"""
import json
import os
import platform
import subprocess
import sys
from datetime import datetime, timezone

SECTION_NOTES = {
    "bench_fit": "One fit trial (issue 12): the fit body for kz-mudcrack-300 (its aspect on a 1 m × 2 cm tile, "
                 "the tet count asked in the name; 64 tabulated load positions), 200 prior draws at age 3, one "
                 "thread, each timed from its draws to Eq. 5: `median_ms`, `mean_ms` run to the end, "
                 "`*_rejecting_ms` with early rejection at the 1 % quantile of the same draws' errors (what a "
                 "20,000-trial best-of-N keeps), `rejected_pct` of them stopped early. Target at 24K: ≤ 5 ms "
                 "median, ≤ 8 ms mean (the paper: ~60 ms).",
    "bench_mesh": "CGAL Mesh_3 tetrahedralisation of the 1 × 1 × 0.05 m tile (facet angle 20°, perturb + exude "
                  "to 12° on the accepted refinement only), one call per size. Target: 24K tets ≤ 1 s. "
                  "`BM_TetrahedralizeWatched`: the same with a never-raised cancel token, as the CLI calls it "
                  "(sliver removal through Fissure's watched CGAL passes, same mesh): the cost of watching.",
    "bench_fracture": "The fracture simulation alone (issue 10), body prepared and σ⁰ computed once: "
                      "simulate_fracture per iteration (/b/c/0) and with the visible pattern and its statistics "
                      "(/b/c/1). b = 0: a structured 1 × 1 × 0.02 m tile of 6,912 tets; 1: a 1 × 1 × 0.1 m slab of "
                      "54,000 tets at r_relax = 5 cm; c: the number of cracks (SimulationOptions::max_cracks on a "
                      "run that would open more). Targets: 7K with 4–5 cracks ≤ 2 ms, 54K with about 270 cracks "
                      "≤ 50 ms (the paper on 2008 hardware: 16 and 264 ms).",
    "bench_fracture_accuracy": "Time against error of the simulation's approximations (issue 10), measured on the "
                               "pattern: the bundled ceramic-tile material on the CGAL 1 × 1 × 0.05 m tile, default "
                               "scenario, 5 seeds; `eq5` = the mean over seeds of the Eq. 5 distance between the "
                               "visible pattern's statistics and the reference's of the same seed (the resistance "
                               "field is a function of position: one seed is one body at every resolution). "
                               "References (`reference_tets`): the finest mesh, direct solve, recovered stress for "
                               "`BM_MeshResolution`; the same mesh's direct recovered σ⁰ for `BM_DirectStress` "
                               "(`recovered=0`: the raw tet stress) and for `BM_ModalStress` (the modal static solve "
                               "with m `modes`, `single_precision=1` expanding with the float copy of Φ, then the same "
                               "recovery, at 24K). `seed_spread`, the noise floor: the mean distance between the "
                               "reference's patterns of two different seeds; `eq5_over_spread` the ratio. "
                               "`sigma0_err_pct`: the volume-weighted relative L2 error of σ⁰'s max principal stress "
                               "over the tets (same mesh only). Time: one trial's simulation for the mesh rows "
                               "(`mesh_s`, `prepare_s`: the one-off CGAL meshing and PreparedBody), one trial's σ⁰ for "
                               "the others (`eigensolve_s`: the one-off modal analysis); `fragments`: mean visible "
                               "fragments. What the figures say: only the mesh resolution is above the noise floor "
                               "({mesh_ratios} the spread at the finest), and it is a bias, not scatter: coarser "
                               "meshes break into fewer visible fragments ({mesh_fragments}). Every σ⁰ "
                               "approximation lands at 0.6–0.85× the spread whatever its field error: the modal "
                               "basis's 14 % (m = 10) to 5.5 % (m = 100) give the same 0.06–0.08 with no trend, "
                               "because the crack sequence is chaotic in σ⁰ — single precision, which leaves σ⁰ equal "
                               "to 4 digits, already moves the pattern 0.02–0.06 from its double twin "
                               "(`eq5_to_double`), and with 5 seeds differences below ≈ 0.02 are not resolved; so at "
                               "24K m = 10 in single precision (≈ 2 ms) is as good, for the pattern, as the direct "
                               "solve (≈ 7 ms). Raw tet stress (35–44 % field error) is also below the floor in "
                               "distance but biases the count up ({raw_fragments}): keep recovery, "
                               "which costs ≈ 2 ms at 24K.",
    "bench_prepare_body": "Per-body preparation, one call per body and size: tetrahedralise + assemble K (the "
                          "ElasticBody) + factor K with supports (the StaticSolver), each stage's process CPU seconds as a "
                          "counter, with the tet count, the meshing attempts and the min dihedral angle. body 0 = "
                          "the 1 × 1 × 0.05 m tile (corner supports), 1 = a unit icosphere (polar cap held), 2 = the "
                          "tile bent to a 1 m radius (ends held). Targets (issue 9): ≤ 1 s at 7K tets, ≤ 1.7 s at "
                          "24K, min dihedral ≥ 10°.",
    "bench_visible_pattern": "The visible crack pattern (issue 10) of the CGAL tile cut by a random hierarchical "
                             "pattern of plane cracks (args: tets, cracks; 7K / 0 is the face's fixed cost, 7K / 5 the issue's 7K "
                             "simulation case): extract_visible_pattern alone (traces, "
                             "junctions, exact fragments on the top face), then with compute_pattern_stats (what a "
                             "fit trial adds to a simulation), and the 1024 px line drawing.",
    "bench_fragments": "Closed fragment meshes and their export (issue 11), one thread: the CGAL 1 × 1 × 0.05 m tile "
                       "at 7K and 54K tets, the bundled default material at its default age, seed 1. "
                       "`MeshFragments`: mesh_fragments (`pieces` closed meshes, `triangles` in all); "
                       "`FragmentScene`: the export scene (UV charts, per-fragment values); `EncodeScene/…/format:F`: "
                       "its bytes in memory, F = 0 GLB, 1 glTF (base64 buffers), 2 OBJ (text), 3 PLY (`MB`: the "
                       "size). `BM_Race` rows are the race's (`bench_race_cell_fracture`, run on 2 threads by "
                       "scripts/race-cell-fracture.sh); here on one.",
    "bench_scene": "Whole scenes (issue 13), one thread (bench.sh; bodies run in parallel on more): "
                   "`Street/slabs:S/cache:C`: the street demo (S slabs in two rows, a curb, a road; S = 24 is "
                   "assets/scenes/street.glb) read from its GLB, every slab and the curb fractured with the "
                   "bundled concrete at age 50 (scripts/demo.sh), the road untouched, the scene exported and "
                   "encoded as GLB in memory, with no cache (C = 0), a cold one emptied before the run (C = 1: its writes paid) or a warm one filled by an earlier run (C = 2: tet meshes and static stress fields read back, what a second run of the scene costs; target ≤ 0.25 s per slab on 2 cores); `cached`: bodies whose mesh came from the cache. `per_body_s`: the time per fractured "
                   "body (target ≤ 1 s on 2 cores); `meshing`, `preparation`, `simulation`, `fragments`: shares "
                   "of the bodies' summed seconds; `export_s`: scene_export + GLB. `OneBodyOf/bodies:B`: one "
                   "slab assigned by its node path in a street of B bodies, against B = 1 (target: within 10 %; "
                   "the other bodies are never meshed, so they cost only reading and export).",
    "bench_race_cell_fracture": "The race (issue 11), by scripts/race-cell-fracture.sh, both sides in one run on this "
                                "machine: Blender 3.4's Cell Fracture add-on (Debian's `blender`, all cores, N seeded "
                                "random points in the 1 × 1 × 0.05 m tile, margin 0; time = the operator; `closed` = "
                                "shards closed after Merge by Distance at 1e-6 m, `closed_as_made` before it: the add-on "
                                "gives each cell its own seam vertices) against Fissure with the body prepared "
                                "(tet mesh, factor, σ⁰ and resistance done once; time = simulating the cracks that give "
                                "about N closed meshes + meshing them, 2 threads, median of 3). `volume_err`: |Σ piece "
                                "volumes − body volume| / body volume. `process_s`: whole processes, `blender -b --python` "
                                "and `fissure fracture tile:1,1,0.05 --tets T --fragments N -o fragments.glb` start to "
                                "exit (`process_pieces`: the closed meshes that run wrote; `--fragments` aims the "
                                "labeller's count, which runs ahead of the meshes' on dense patterns). `speedup`: "
                                "Blender's time / Fissure's. Targets: ≥ 10× at 50 pieces, ≥ 30× at 1000, every piece "
                                "closed. `machine:` rows are bench_machine's from the same run.",
    "bench_race_street_cell_fracture": "The street race (issue 13), by scripts/race-street-cell-fracture.sh, both "
                                       "sides in one run on this machine, whole processes start to exit, medians of 3: "
                                       "Fissure (`fissure scene fracture assets/scenes/street.glb`, scripts/demo.sh's "
                                       "assignments, age 50, 2 threads, an empty cache (`cold`) and the cache it filled "
                                       "(`warm`)) against Blender 3.4 (Debian's `blender`, all cores) importing the same "
                                       "GLB, giving every body Fissure fractured as many uniform seed points in its "
                                       "bounding box as Fissure made fragments of it, breaking them all with one Cell "
                                       "Fracture call (margin 0) and exporting a GLB. `closed`: pieces closed in Blender "
                                       "(Fissure's after Merge Vertices, by scripts/blender_check_scene.py; Blender's "
                                       "after Merge by Distance at 1e-6 m, `closed_as_made` before it). `bodies_s`: "
                                       "Fissure's per-body seconds summed over its threads, split into the shares "
                                       "`meshing`, `preparation`, `simulation`, `fragments`. `fracture_s`, `import_s`, "
                                       "`export_s`: Blender's operator, glTF import and export alone. `volume_err`: "
                                       "|Σ piece volumes − bodies' volume| / bodies' volume. `speedup`: Blender's "
                                       "process time / Fissure's (Cell Fracture cuts Voronoi cells; Fissure solves the "
                                       "stress and grows the cracks it drives). `machine:` rows are bench_machine's "
                                       "from the same run.",
    "bench_msh": "gmsh MSH 4.1 write and read through the gmsh API.",
    "bench_fem": "FEM kernels on the CGAL tile (corner supports, 10 kN on a 5 cm centre patch). Targets at 24K "
                 "tets: assemble K ≤ 50 ms (`AssembleStiffness` reuses the pattern; `FromScratch` includes "
                 "gradients and pattern), factor ≤ 100 ms (`threads`: the process's threads afterwards, 1 on one thread), direct solve ≤ 3 ms (includes the residual check), "
                 "50 modes ≤ 0.6 s (`Eigensolve50/N/1` supported, `/0` free), modal solve m = 50 ≤ 0.1 ms, "
                 "`EigensolveFewModes/N/m`: m = 10 and 20 modes, supported (no target; blocks of 4 at 7K, 8 at 24K). "
                 "`BlockSolve/N/r`: r right-hand sides solved together with one factor (`us_per_rhs` per column; "
                 "1 is CHOLMOD's supernodal solve, blocks go through Fissure's kernel, the eigensolver's 8 at a time), "
                 "stress + max principal ≤ 0.5 ms. `StressRecoveryBuild` / `Apply`: the patch-recovery operator, "
                 "built once per mesh and applied once per stress field (no target). `ModalSolve50/N/p`: p = 0 double, p = 1 the float copy of Φ "
                 "(ModalPrecision::Single). The modal solve streams Φ once (`phi_MB`): it is memory-bound, so read it against "
                 "`bench_machine`'s bandwidth beyond L2 (6.7 MB in double, 3.3 MB in float at 24K; the "
                 "machines of this project read 21–75 GB/s there, which puts the floor at 0.09–0.3 ms). "
                 "The float copy's error is in `bench_modal_accuracy`.",
    "bench_materials": "Per-trial and per-command costs of the fracture parameters, one thread. "
                       "`DrawResistance/tets:N/spread:S`: the per-tet resistance field (draw_resistance), R_cvar = "
                       "S % of R_cm; at S = 100 (Table 3's largest) 17 % of the normal draws fall below the "
                       "0.05·R_cm floor and are resampled. `ReadMaterial`: parse and validate the default "
                       "material file from memory.",
    "bench_mesh_convergence": "Time against error of the mesh resolution: the bench_fem load case solved directly "
                              "on tiles of increasing tet count, against a 200K-tet reference (`reference_tets`). "
                              "Time = meshing + assembly + factorisation + solve + stress. Errors in %: compliance "
                              "fᵀu; the volume mean (`centre_mean`) and peak (`centre_peak`) of the max principal "
                              "stress over the bottom half under the centre (|x|, |y| ≤ 0.1 m); the peak over the "
                              "whole tile (`global_peak`, at the edges of the 5 cm corner supports: a stress "
                              "concentration that does not converge). Linear tets lock in bending with 1–3 elements "
                              "through 5 cm, so the tile converges slowly and from the stiff side: the reference itself "
                              "is ≈ 11 % too stiff by Richardson extrapolation of the last three levels (rate h^1.65). "
                              "Patterns: the max principal stress on a 41 × 41 grid, each field scaled to unit RMS, "
                              "relative L2 against the reference. `pattern`: the raw tet values in the plane z = T/4, "
                              "dominated by the scatter of constant-stress tets through a bending plate; "
                              "`recovered_pattern`: the patch-recovered nodal stress (StressRecovery) interpolated "
                              "there; `smooth_pattern`: the raw values averaged over 3 cm of the bottom half. "
                              "Recovery turns a 62 % element-scale pattern error into 7 % at 24K "
                              "(docs/architecture.md).",
    "bench_modal": "Modal analysis (block shift-invert Krylov–Schur over multi-RHS CHOLMOD solves) and the modal static solve.",
    "bench_modal_accuracy": "Time against error of the modal static solve against the direct solve on the 24K "
                            "tile, 10 kN on a 5 cm centre patch. `supported=1`: corner supports; `0`: free body "
                            "(inertia relief). Time = modal solve + stress kernel; `eigensolve_s` = the one-off "
                            "modal analysis for that m; `direct_solve_and_stress_ms` = the exact alternative. "
                            "Errors: displacement L2, volume-weighted stress-tensor L2, and the peak max "
                            "principal stress, in %. `single_precision=1` rows expand with the float copy of Φ: "
                            "their errors differ from the double rows' by ≤ 0.001 percentage points, so the "
                            "precision costs nothing against truncation.",
    "bench_cli_memory": "Peak resident memory of the whole `fissure solve` process (read, assemble, factor or "
                        "eigensolve, stress, write), measured on a child process. Target: ≤ 400 MB with 50 modes "
                        "on the 54K tile.",
    "bench_machine": "The machine itself, to read the other sections against: one core's streaming read "
                     "bandwidth by working-set size (`working_set_MB`) and its double-precision FMA throughput. "
                     "The modal solve and the stress kernel are bound by the first, assembly and factorisation "
                     "by the second. Shared virtual machines differ from day to day by up to 2×: compare a "
                     "regression against this section of the same run.",
    "bench_startup": "What every command pays before any work, from exec to exit: `fissure --version` "
                     "(answered by the dispatcher) and each command's `--help` (its own executable started and "
                     "its options parsed). `peak_rss_mb`: the process's peak resident memory; `shared_libs`: "
                     "distinct shared libraries the loader initialised (`LD_DEBUG=libs`). Targets: --version "
                     "≤ 50 ms, ≤ 30 MB, ≤ 60 libraries; no command loads a library it does not use. Before the "
                     "split into one executable per command every command initialised 44 libraries "
                     "(204 before issue 8's own MSH writer and image decoders).",
    "bench_exemplar": "Exemplar analysis: traced mask to crack graph to statistics. Second argument: 0 = a "
                      "hierarchical network of orthogonal cracks (≈ 1,100 cracks; the issue's targets: 1024² ≤ 50 ms, "
                      "4096² ≤ 1 s, ≤ 300 MB), 1 = a dense oblique grid (≈ 29,000 crossings at 4096², thousands "
                      "of close junction pairs to contract: the stress case).",
}

UNIT_SCALE = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


def medians_of(benchmarks):
    medians = [b for b in benchmarks if b.get("aggregate_name", "median") == "median"]
    return medians or [b for b in benchmarks if "aggregate_name" not in b]


def mesh_resolution_figures(benchmarks):
    """The figures bench_fracture_accuracy's note quotes, read from its BM_MeshResolution rows."""
    rows = sorted((b for b in medians_of(benchmarks) if b.get("run_name", b["name"]).startswith("BM_MeshResolution")),
                  key=lambda b: b["tets"])
    if not rows:
        return {"mesh_ratios": "not run", "mesh_fragments": "not run", "raw_fragments": "not run"}
    label = lambda b: f"{round(b['tets'] / 1000)}K"
    direct = {(b["tets"], b.get("recovered")): b for b in medians_of(benchmarks)
              if b.get("run_name", b["name"]).startswith("BM_DirectStress")}
    raw = [f"{direct[(t, 0)]['fragments']:.0f} raw against {direct[(t, 1)]['fragments']:.0f} recovered at "
           f"{round(t / 1000)}K" for t in sorted({t for t, _ in direct}) if (t, 0) in direct and (t, 1) in direct]
    return {
        "raw_fragments": "; ".join(raw) or "not run",
        "mesh_ratios": ", ".join(f"{label(b)} {b['eq5_over_spread']:.2f}×" for b in rows[:-1]),
        "mesh_fragments": ", ".join(f"{b['fragments']:.0f}" for b in rows) + " at " +
                          ", ".join(label(b) for b in rows),
    }


# Notes whose figures are filled in from the section's own results.
NOTE_FIGURES = {"bench_fracture_accuracy": mesh_resolution_figures}


def machine():
    cpu = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} logical cores, {platform.system()} {platform.release()}"


def commit(root):
    try:
        sha = subprocess.check_output(["git", "-C", root, "rev-parse", "--short", "HEAD"], text=True).strip()
        dirty = subprocess.call(["git", "-C", root, "diff", "--quiet", "HEAD"]) != 0
        return sha + (" (with uncommitted changes)" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def fmt(value):
    if isinstance(value, float):
        if value == 0:
            return "0"
        magnitude = abs(value)
        if magnitude >= 1e5 or magnitude < 1e-3:
            return f"{value:.3g}"
        if magnitude >= 100:
            return f"{value:.0f}"
        return f"{value:.3g}"
    return str(value)


def table(benchmarks):
    medians = medians_of(benchmarks)
    skip = {"name", "run_name", "run_type", "repetitions", "repetition_index", "threads",
            "iterations", "real_time", "cpu_time", "time_unit", "aggregate_name",
            "aggregate_unit", "family_index", "per_family_instance_index", "label", "error_occurred",
            "error_message"}
    counters = []
    for b in medians:
        for key in b:
            if key not in skip and key not in counters:
                counters.append(key)
    header = ["benchmark", "time (ms, median)"] + counters
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for b in medians:
        name = b.get("run_name", b["name"]).replace("_median", "")
        ms = b["real_time"] * UNIT_SCALE.get(b.get("time_unit", "ns"), 1e-6)
        row = [f"`{name}`", fmt(ms)] + [fmt(b[c]) if c in b else "" for c in counters]
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)


def main():
    results_dir, output, command = sys.argv[1], sys.argv[2], sys.argv[3]
    root = os.path.dirname(os.path.dirname(os.path.abspath(output)))
    # Keep sections of binaries that were not re-run this time.
    sections = {}
    if os.path.exists(output):
        current, buf = None, []
        with open(output) as f:
            for line in f:
                if line.startswith("## `bench_"):
                    if current:
                        sections[current] = "".join(buf)
                    current, buf = line.split("`")[1], [line]
                elif current:
                    buf.append(line)
        if current:
            sections[current] = "".join(buf)
    for fname in sorted(os.listdir(results_dir)):
        if not fname.endswith(".json"):
            continue
        name = fname[:-5]
        with open(os.path.join(results_dir, fname)) as f:
            data = json.load(f)
        commit_file = os.path.join(results_dir, name + ".commit")
        run_commit = open(commit_file).read().strip() if os.path.exists(commit_file) else commit(root)
        # The command that ran this binary (a later filtered run re-reads older results).
        command_file = os.path.join(results_dir, name + ".command")
        run_command = open(command_file).read().strip() if os.path.exists(command_file) else command
        note = SECTION_NOTES.get(name, "")
        if name in NOTE_FIGURES:
            note = note.format(**NOTE_FIGURES[name](data["benchmarks"]))
        stamp = data.get("context", {}).get("date", "")
        sections[name] = (f"## `{name}`\n\n{note}\n\nRun {stamp} on {machine()}, commit {run_commit}, "
                          f"command `{run_command}`.\n\n{table(data['benchmarks'])}\n\n")
    with open(output + ".tmp", "w") as f:
        f.write("# Benchmarks\n\n")
        f.write("Generated by `scripts/bench.sh` (do not edit by hand): one core (`taskset -c 0`, "
                "`OPENBLAS_NUM_THREADS=1`), medians of 5 repetitions. Targets and the gaps are "
                "discussed in the issue notes and in docs/architecture.md.\n\n")
        for name in sorted(sections):
            f.write(sections[name])
    os.replace(output + ".tmp", output)


if __name__ == "__main__":
    main()
