# Blender's Mantaflow liquid on the dam break of `pbm bench liquid` (app/bench_liquid.cpp): a 1 m
# cube domain of N^3 cells with closed walls, a column 0.4 m x 1 m x 0.6 m at x = 0, FLIP, no
# mesh, no particles beyond FLIP's own. Each resolution is baked twice, with exactly 1 and
# exactly 2 substeps a frame (adaptive steps clamped by timesteps_min = timesteps_max; with
# adaptive steps off Blender 3.4 ignores the count), and the difference is the substeps' cost
# without the per-frame cache writes (29 ms a frame at 32^3 here: measured 1, 2 and 4 substeps a
# frame, 1.97, 3.07 and 5.26 s for 30 frames, i.e. 36.6 ms a substep either way). Prints per
# resolution:
#   mantaflow N <cells> ns_per_cell_substep <value> per_frame_ms <cache and set-up per frame>
# Run (Debian: apt-get install blender):
#   blender -b --factory-startup -noaudio -P bench/mantaflow_dam_break.py -- 32 64
# `pbm bench liquid` runs it itself when `blender` is on PATH and prints the ratio in the same run.
import shutil
import sys
import tempfile
import time

import bpy


def bake(n, frames, substeps):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps = 30
    scene.frame_start = 1
    scene.frame_end = frames

    bpy.ops.mesh.primitive_cube_add(size=1, location=(0.5, 0.5, 0.5))
    domain = bpy.context.active_object
    fluid = domain.modifiers.new("Fluid", "FLUID")
    fluid.fluid_type = "DOMAIN"
    ds = fluid.domain_settings
    ds.domain_type = "LIQUID"
    ds.resolution_max = n
    ds.use_adaptive_timesteps = True
    ds.timesteps_min = substeps
    ds.timesteps_max = substeps
    ds.use_mesh = False
    ds.use_spray_particles = False
    ds.use_foam_particles = False
    ds.use_bubble_particles = False
    ds.cache_type = "ALL"
    ds.cache_frame_start = 1
    ds.cache_frame_end = frames
    cache = tempfile.mkdtemp(prefix="pbm-mantaflow-")
    ds.cache_directory = cache

    bpy.ops.mesh.primitive_cube_add(size=1, location=(0.2, 0.5, 0.3), scale=(0.4, 1.0, 0.6))
    column = bpy.context.active_object
    flow = column.modifiers.new("Fluid", "FLUID")
    flow.fluid_type = "FLOW"
    fs = flow.flow_settings
    fs.flow_type = "LIQUID"
    fs.flow_behavior = "GEOMETRY"
    fs.flow_source = "MESH"

    bpy.context.view_layer.objects.active = domain
    domain.select_set(True)
    start = time.perf_counter()
    with bpy.context.temp_override(active_object=domain, object=domain,
                                   selected_objects=[domain]):
        bpy.ops.fluid.bake_data()
    seconds = time.perf_counter() - start
    shutil.rmtree(cache, ignore_errors=True)
    return seconds


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    sizes = [int(a) for a in args] or [32, 64]
    for n in sizes:
        frames = 30 if n <= 32 else 10
        one, two = bake(n, frames, 1), bake(n, frames, 2)
        cells = n * n * n
        substep = max(two - one, 0.0) / frames
        print("mantaflow %d %d ns_per_cell_substep %.1f per_frame_ms %.1f" %
              (n, cells, substep / cells * 1e9, (one / frames - substep) * 1e3), flush=True)


main()
