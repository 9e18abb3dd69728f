"""relax direct on 1 and 3 threads (``lattice/quasistatic ... relax direct threads N``).

The threads run the sparse factor's factorisations and solves and the loops over the whole
network (forces, stretches, the line search's energy change, the worst spring, the longest
move), in blocks of a fixed size whose results are combined in the serial loop's order. So
the run must be the same to the bit on any number of threads: the same breaks with the same
ratios, the same strains and stresses, the same final bond records.

The scene: layer extension, 60 particles per row (4200 particles, 12,341 springs: several
blocks of springs and of nodes), 12 strain steps (302 breaks, 28 contacts closed). About 5 s
per run.
"""

from __future__ import annotations

from bonded_lattice.scene_study import run_scene
from bonded_lattice.scenes import Scene, break_sequence, read_scene_dat


def test_relax_direct_gives_the_same_run_on_one_and_three_threads(tmp_path):
    runs = {}
    for threads in (1, 3):
        scene = Scene("layer-extension", n_x=60, n_steps=12, relax="direct", threads=threads)
        runs[threads] = tmp_path / f"threads{threads}"
        run_scene(scene, runs[threads], pictures=False)
    one, three = runs[1], runs[3]
    assert len(break_sequence(one)) > 200, "the test must break many bonds"
    assert read_scene_dat(one / "scene.dat")["contacts"][-1] > 0, "the test must close contacts"
    for name in ("breaks.txt", "scene.dat", "bonds.final.txt"):
        assert (three / name).read_bytes() == (one / name).read_bytes(), name
