"""LatticeSparseCholesky (src/BONDED_LATTICE/lattice_sparse_cholesky.h), compiled standalone with
its check driver tests/cpp/sparse_cholesky_check.cpp, against a dense Cholesky of the explicitly
assembled stiffness matrix (the driver builds the networks and prints the numbers asserted here)."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SOURCES = [ROOT / "tests" / "cpp" / "sparse_cholesky_check.cpp",
           ROOT / "src" / "BONDED_LATTICE" / "lattice_sparse_cholesky.cpp"]

# the largest unknown count of the networks is 768 (fcc, 256 nodes) with stiffnesses in [0.5, 1.5):
# cond(K) is below ~1e4, so a backward-stable Cholesky leaves a relative residual of about
# n eps cond < 1e-11 and differs from the dense solve by about eps cond < 1e-11
SOLVE_TOL = 1e-10
# 60 rank-one changes each add rounding of about eps ||L||^2 to the factor; with shift 1e-3
# (some nodes may come loose) cond(K) stays below ~1e4, so the changed factor's solve agrees
# with a fresh factorisation to about 60 eps cond < 1e-10
MODIFY_TOL = 1e-9


@pytest.fixture(scope="module")
def check(tmp_path_factory) -> dict:
    """The driver's "name value" lines as a dict, its error messages under "messages"."""
    gxx = shutil.which("g++")
    if gxx is None:
        pytest.skip("no g++ on PATH: the standalone solver check needs a C++17 compiler")
    exe = tmp_path_factory.mktemp("cholesky") / "sparse_cholesky_check"
    subprocess.run([gxx, "-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror", "-pthread",
                    f"-I{ROOT / 'src' / 'BONDED_LATTICE'}", *map(str, SOURCES), "-o", str(exe)],
                   check=True, timeout=120)
    out = subprocess.run([str(exe)], check=True, capture_output=True, text=True, timeout=60)
    values: dict = {"messages": [], "text": out.stdout}
    for line in out.stdout.splitlines():
        name, _, rest = line.partition(" ")
        if name == "message":
            values["messages"].append(rest)
        else:
            values[name] = float(rest)
    return values


@pytest.mark.parametrize("tag", ["tri", "tri_leaf1", "fcc", "two_patches"])
def test_solve_matches_assembled_matrix(check, tag):
    # 2D triangular 10 x 12 (held rows and random held components; leaf size 16 and 1, the
    # latter a deep tree of single-node blocks) and 3D fcc of 256 nodes
    assert check[f"{tag}_residual"] <= SOLVE_TOL, check["text"]
    assert check[f"{tag}_vs_dense"] <= SOLVE_TOL
    # solve() leaves the held entries as they were
    assert check[f"{tag}_held_untouched"] == 1.0
    # a real separator tree, not one dense block
    assert check[f"{tag}_ntree"] > 1 and check[f"{tag}_depth"] > 1
    # the accessors' documented properties: contiguous columns in post-order, parents after
    # children, R_t sorted ancestor columns, children, subtrees [first_descendant(t), t],
    # zeros above the diagonal of each block
    assert check[f"{tag}_tree_violations"] == 0
    # forward_block over all blocks, then back_block on one leaf node's path to the root only:
    # that node's entries of solve(), bit for bit (the same operations in the same order)
    assert check[f"{tag}_path_back_mismatches"] == 0
    assert 1 < check[f"{tag}_path_back_steps"] < check[f"{tag}_ntree"]


def test_disconnected_network_is_a_forest(check):
    # two 8 x 6 patches with no spring between them: two separator trees, one per patch
    assert check["two_patches_roots"] == 2
    assert check["tri_roots"] == 1 and check["fcc_roots"] == 1


def test_all_held(check):
    # no free component: no columns, no tree, no entries; solve leaves every entry as it was
    assert check["all_held_entries"] == 0.0
    assert check["all_held_untouched"] == 1.0


def test_leaf_size_one_dissects_further(check):
    # smaller leaves: more tree nodes and a deeper tree on the same network
    assert check["tri_leaf1_ntree"] > check["tri_ntree"]
    assert check["tri_leaf1_depth"] > check["tri_depth"]


@pytest.mark.parametrize("tag", ["tri2", "fcc"])
def test_updates_and_downdates_match_fresh_factorisation(check, tag):
    # 50 random downdates then 10 updates (re-added springs, new stiffness)
    assert check[f"{tag}_modified_vs_fresh"] <= MODIFY_TOL, check["text"]
    assert check[f"{tag}_modified_vs_dense"] <= MODIFY_TOL
    assert check[f"{tag}_modified_residual"] <= MODIFY_TOL


def test_node_cut_loose(check):
    # all 6 springs of an interior node removed by downdates, shift 1e-10
    assert check["loose_springs_cut"] == 6
    assert check["loose_zero_force_finite"] == 1.0
    assert check["loose_with_force_finite"] == 1.0
    # without a force on the loose node (the quasi-static case: its springs are gone) the rest
    # is the solution of the network without it: the downdates leave couplings of rounding size
    # (eps k) to the node, which has nothing to transmit
    assert check["loose_zero_force_rest_vs_reference"] <= 1e-6, check["text"]
    # its own displacement is then those couplings over shift: eps k / shift ~ 2e-6 of the rest's
    assert check["loose_zero_force_node"] <= 1e-5
    # with a force b_u on it, x_u = b_u / shift ~ 1e10 |b| and the rounding couplings pass
    # eps k |x_u| ~ eps k / shift ~ 2e-6 |b| to the rest
    assert check["loose_with_force_rest_vs_reference"] <= 1e-5
    assert check["loose_with_force_node"] <= 1e-5


def test_errors_are_caught_with_their_messages(check):
    assert check["error_modify_outside_pattern"] == 1.0
    assert check["error_factorise_outside_pattern"] == 1.0
    assert check["error_indefinite_downdate"] == 1.0
    assert any("modify (downdate): pivot -" in m for m in check["messages"]), check["messages"]
    # a failed downdate restores the columns it changed: the same solve to the last bit
    assert check["error_factor_unchanged_after_failed_downdate"] == 0.0
    # a node without springs and shift 0: a zero pivot naming it; no factor afterwards
    assert check["error_pivot_names_node"] == 1.0
    assert check["error_factorised_after_failure"] == 0.0


def test_deterministic(check):
    # the same input twice (analyse, factorise, 5 downdates, solve): bit-identical
    assert check["deterministic"] == 1.0


@pytest.mark.parametrize("tag", ["tri_big", "tri_big_leaf2", "fcc_big", "two_big"])
def test_threads_give_the_same_bits(check, tag):
    # factorise, solve, 20 downdates + 5 updates, solve, factorise again, solve, on 1, 2, 3 and
    # 4 threads (2D triangular 60 x 50, leaf sizes 8 and 2; 3D fcc of 864 nodes; two separate
    # 40 x 30 patches, a forest of two trees): every factor
    # and solution equal to 1 thread's to the bit (memcmp), also when one object changes its
    # thread count between solves
    assert check[f"{tag}_threads_mismatches"] == 0, check["text"]
    assert check[f"{tag}_threads_switch_mismatches"] == 0
    # the threaded paths were taken: no tasks on 1 thread, several subtrees on 2 to 4
    assert check[f"{tag}_threads1_solve_tasks"] == 0
    assert check[f"{tag}_threads1_factorise_tasks"] == 0
    for nt in (2, 3, 4):
        assert check[f"{tag}_threads{nt}_solve_tasks"] >= 2
        assert check[f"{tag}_threads{nt}_factorise_tasks"] >= 2
    # the fcc's largest front has more than 128 rows below its first 64-column panel: the
    # rank-k updates of the top fronts were split over the threads (SYRK_PARALLEL_ROWS)
    if tag == "fcc_big":
        assert check[f"{tag}_max_rows"] > 128 + 64


def test_threads_report_the_serial_pivot_error(check):
    # two nodes without springs (one in each half), shift 0: the same message (the first bad
    # pivot in post-order) on 1 to 4 threads, where the two may fail in different tasks
    assert check["threads_error_same"] == 4
    assert check["threads_error_tasks"] >= 2
    assert check["threads_error_names_a_node"] == 1


def test_set_threads_range(check):
    assert check["default_threads"] == 1
    assert check["error_set_threads"] == 2
    assert any("threads 0 is out of range (>= 1)" in m for m in check["messages"])
